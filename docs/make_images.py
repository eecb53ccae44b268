"""Make the documentation's pictures: the head camera's image and depth at rest, the operator's
view under each modality at the same moment, and the predictive ghost ahead of a delayed view.

Seed 0's synthetic operator under full AR, 6 s into the trial (10 cm from the grasp point), at the
Kinect's 640x480; headless Chromium takes each picture of the view (needs ``apt-get install
chromium``). The predictive ghost: the same seed under the ghost and the predictive ghost with a
500 ms round trip, while the arm reaches.

    python docs/make_images.py [--out docs/images]
"""

from __future__ import annotations

from arteleop import blas_kernel  # noqa: F401  (first: it picks numpy's BLAS kernel)

# isort: split
import argparse
import sys
import tempfile
from dataclasses import replace
from pathlib import Path

import cv2

from arteleop.ar_features import MODALITIES, STUDY_MODALITIES, OperatorView, ViewConfig
from arteleop.scene import RemoteSite, write_snapshot
from arteleop.teleop import (
    NetworkConfig,
    TrialConfig,
    display_frame_at,
    trial_operator,
    view_assets,
)

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # the checkout's tests/instruments
from tests.instruments.browser import browser_page

MOMENT_S = 6.0
DELAYED_MOMENT_S = 6.0
"""Seed 0 reaches for the bowl then, in view: the predicted gripper is 19 cm ahead."""
WIDTH_PX = 800
"""The pictures are scaled down to this width for the documentation."""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--out", type=Path, default=Path(__file__).parent / "images")
    out: Path = parser.parse_args().out
    out.mkdir(parents=True, exist_ok=True)
    config = TrialConfig(seed=0)
    with RemoteSite(config.site) as site, tempfile.TemporaryDirectory() as tmp:
        snapshot = write_snapshot(site, Path(tmp))
        for name in ("rgb.png", "depth_vis.png"):
            path = out / f"camera_{name}"
            _write(path, cv2.imread(str(snapshot.files[name])), WIDTH_PX / 2)
            print(f"wrote {path}")
    with RemoteSite(config.site) as site:
        source = trial_operator(site, config)
        frame = display_frame_at(source, config, MOMENT_S, site)
        assets = view_assets(site)
    with OperatorView(ViewConfig(port=0), assets) as view:
        view.show(frame)
        with browser_page(view.url) as page:
            for name in STUDY_MODALITIES:
                view.show(replace(frame, cues=MODALITIES[name]))
                path = out / f"view_{name}.png"
                shot = page.screenshot(path)
                _write(path, cv2.cvtColor(shot, cv2.COLOR_RGB2BGR), WIDTH_PX)
                print(f"wrote {path}")
    delayed = TrialConfig(
        seed=0, modality="embodiment+predictive", network=NetworkConfig(delay_s=0.25)
    )
    with RemoteSite(delayed.site) as site:
        source = trial_operator(site, delayed)
        frame = display_frame_at(source, delayed, DELAYED_MOMENT_S, site)
    with OperatorView(ViewConfig(port=0), assets) as view:
        view.show(frame)
        with browser_page(view.url) as page:
            view.show(frame)
            path = out / "view_predictive_500ms.png"
            shot = page.screenshot(path)
            _write(path, cv2.cvtColor(shot, cv2.COLOR_RGB2BGR), WIDTH_PX)
            print(f"wrote {path}")


def _write(path: Path, bgr: cv2.typing.MatLike, width_px: float) -> None:
    """Write an image scaled down to ``width_px``."""
    scale = width_px / bgr.shape[1]
    cv2.imwrite(str(path), cv2.resize(bgr, None, fx=scale, fy=scale, interpolation=cv2.INTER_AREA))


if __name__ == "__main__":
    main()

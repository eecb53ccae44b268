"""What the operator's view sends a browser: bytes per camera frame, and the rate a connection
must carry at 15 and 30 frames a second.

A seeded full-AR trial (seed 0) renders every camera frame at 640x480, as ``arteleop study
serve`` does (the cloud thinned by ``CLOUD_STRIDE``), from ``--from-s`` for ``--seconds`` of
simulated time; each frame goes to an :class:`OperatorView` with one headless client connected
(``tests/instruments/view_probe.py``), which counts the bytes that reach its socket after each
frame. The first frame (the whole scene, once) is reported apart. With ``--baseline REF`` the
same frames run through a git worktree of REF first, side by side.

    python benchmarks/bench_stream.py [--from-s 4] [--seconds 10] [--baseline REF]
"""

from __future__ import annotations

from arteleop import blas_kernel  # noqa: F401  (first: it picks numpy's BLAS kernel)

# isort: split
import os

os.environ.setdefault("OMP_NUM_THREADS", "1")

import argparse
import json
import subprocess
import sys
import time

import numpy as np
from bench_speed import ROOT, baseline_tree  # benchmarks/, the script's folder

sys.path.insert(0, str(ROOT))  # the checkout's tests/instruments


def measure(from_s: float, seconds: float) -> dict[str, object]:
    """Bytes the client received after each frame shown from ``from_s`` (s) on."""
    from arteleop.ar_features import DisplayFrame, OperatorView, ViewConfig
    from arteleop.scene import HeadCameraConfig, RemoteSite, SiteConfig
    from arteleop.teleop import TrialConfig, run_trial, trial_operator, view_assets
    from tests.instruments.view_probe import ViewProbe

    camera = HeadCameraConfig(width_px=640, height_px=480)
    config = TrialConfig(modality="full", seed=0, timeout_s=from_s + seconds,
                         render_camera=True, site=SiteConfig(camera=camera))  # fmt: skip
    sizes: list[int] = []
    points: list[int] = []
    with RemoteSite(config.site) as site:
        with (
            OperatorView(ViewConfig(port=0), view_assets(site)) as view,
            ViewProbe(view.url) as probe,
        ):
            time.sleep(0.5)

            def received() -> int:
                return sum(len(m.data) for m in probe.messages())

            class Counting:
                def show(self, frame: DisplayFrame) -> None:
                    if frame.time_s < from_s or frame.cloud_points_m is None:
                        return
                    before = received()
                    view.show(frame)
                    view.server.flush()
                    # Until the socket has been quiet for 30 ms: the frame is in.
                    last, quiet_from = before, time.perf_counter()
                    while time.perf_counter() - quiet_from < 0.03:
                        time.sleep(0.005)
                        now = received()
                        if now != last:
                            last, quiet_from = now, time.perf_counter()
                    sizes.append(last - before)
                    points.append(len(frame.cloud_points_m))

            run_trial(trial_operator(site, config), config, site, Counting())
    return {"bytes": sizes, "points": points}


def _row(name: str, run: dict[str, object], base: float | None) -> str:
    sizes = np.asarray(run["bytes"][1:], dtype=float)  # after the first, the whole scene
    median, p95 = np.median(sizes), np.percentile(sizes, 95)
    mbit = lambda fps: sizes.mean() * 8 * fps / 1e6  # noqa: E731
    ratio = "" if base is None else f"{sizes.mean() / base:.3f}"
    return (
        f"| {name} | {run['bytes'][0] / 1e3:.0f} | {median / 1e3:.1f} | {p95 / 1e3:.1f} | "
        f"{sizes.mean() / 1e3:.1f} | {mbit(15):.1f} | {mbit(30):.1f} | {ratio} |"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--from-s", type=float, default=4.0)
    parser.add_argument("--seconds", type=float, default=10.0)
    parser.add_argument("--baseline", help="the same frames through this commit first")
    parser.add_argument("--worker", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.worker:
        print(json.dumps(measure(args.from_s, args.seconds)))
        return
    trees = {"this checkout": ROOT}
    if args.baseline:
        trees = {f"baseline {args.baseline}": baseline_tree(args.baseline), **trees}
    runs = {}
    for name, tree in trees.items():
        env = {**os.environ, "PYTHONPATH": str(tree)}
        command = [sys.executable, __file__, "--worker", "--from-s", str(args.from_s),
                   "--seconds", str(args.seconds)]  # fmt: skip
        out = subprocess.run(command, cwd=tree, env=env, check=True, capture_output=True,
                             text=True).stdout  # fmt: skip
        runs[name] = json.loads(out.strip().splitlines()[-1])
    print(f"\nFull AR, seed 0, 640x480, frames {args.from_s:g}-{args.from_s + args.seconds:g} s:"
          f" {len(next(iter(runs.values()))['bytes'])} frames\n")  # fmt: skip
    print(
        "| stream | first frame (kB) | median (kB) | p95 (kB) | mean (kB) | Mbit/s at 15 fps "
        "| at 30 fps | mean / baseline |"
    )
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    base = None
    for name, run in runs.items():
        print(_row(name, run, base))
        base = base or float(np.mean(run["bytes"][1:]))


if __name__ == "__main__":
    main()

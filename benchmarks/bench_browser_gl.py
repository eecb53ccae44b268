"""What a headless Chromium without a GPU costs to show the operator's view, per WebGL backend:
Mesa's llvmpipe (ANGLE's GL ES backend, the suite's browser) against Chromium's SwiftShader,
side by side.

A seeded full-AR trial (seed 0) gives 30 display frames from 5 s on, at 320x240 (the browser
tests' camera). Each backend's Chromium opens one tab of an :class:`OperatorView` at the
suite's 1280x800. Still: the first frame shown and left, Chromium's processor time (all its
processes, from ``/proc``) over ``--windows`` windows of 5 s, after 5 s to settle. Streaming:
the frames shown in turn for 10 s, a fifteenth of a second's pause after each (the server's own
time to send one comes on top: the rate reached is reported), the page's animation frames
counted as a served participant's page counts them (:mod:`arteleop.ar_features.page_frames`)
and Chromium's processor time meanwhile. Medians of the windows; the backends run one after the
other, ``--rounds`` times, alternating.

    python benchmarks/bench_browser_gl.py [--rounds 2] [--windows 3]
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from dataclasses import replace
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))  # the checkout's tests/instruments

RENDERER = (
    "() => { const gl = document.createElement('canvas').getContext('webgl2');"
    " const info = gl.getExtension('WEBGL_debug_renderer_info');"
    " return gl.getParameter(info.UNMASKED_RENDERER_WEBGL); }"
)


def chromium_cpu_s() -> float:
    """Processor time (user and system, s) of every Chromium process now running."""
    tick = os.sysconf("SC_CLK_TCK")
    total = 0.0
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            stat = Path(f"/proc/{pid}/stat").read_text()
        except OSError:
            continue
        name = stat[stat.index("(") + 1 : stat.rindex(")")]
        if "chrom" in name:
            fields = stat[stat.rindex(")") + 2 :].split()
            total += (int(fields[11]) + int(fields[12])) / tick
    return total


def newest_client(view, wait_s: float = 30.0):
    """The view's last tab to connect (viser lists a tab once it has sent its camera)."""
    deadline = time.monotonic() + wait_s
    while not (clients := view.server.get_clients()) and time.monotonic() < deadline:
        time.sleep(0.1)
    if not clients:
        sys.exit(f"bench_browser_gl: no tab connected to {view.url} within {wait_s:.0f} s")
    return clients[max(clients)]


def measure(view, frames, webgl: list[str], windows: int) -> dict[str, object]:
    """One backend (Chromium's ``webgl`` arguments) on ``view``: its still and streaming
    costs."""
    from arteleop.ar_features.page_frames import frame_counter_html, frames_between, read_count
    from tests.instruments.browser import chromium

    view.show_still(frames[0])
    with chromium(webgl) as launched:
        page = launched.open(view.url, for_pictures=False).playwright
        renderer = page.evaluate(RENDERER)
        # The page counts its frames as a served participant's does (browser.csv's page_fps).
        client = newest_client(view)
        client.gui.add_html(frame_counter_html(client.client_id))
        time.sleep(5.0)
        still = []
        for _ in range(windows):
            before, start = chromium_cpu_s(), time.monotonic()
            time.sleep(5.0)
            still.append((chromium_cpu_s() - before) / (time.monotonic() - start))
        before, start, k = chromium_cpu_s(), time.monotonic(), 0
        first = read_count(client)
        while time.monotonic() - start < 10.0:
            view.show(frames[k % len(frames)])
            k += 1
            time.sleep(1 / 15)
        elapsed_s = time.monotonic() - start
        streaming = (chromium_cpu_s() - before) / elapsed_s
        _, page_fps = frames_between(first, read_count(client))
    return {"renderer": renderer, "still": statistics.median(still),
            "streaming": streaming, "page_fps": page_fps, "sent_fps": k / elapsed_s}  # fmt: skip


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=2, help="each backend this many times")
    parser.add_argument("--windows", type=int, default=3, help="5 s windows of the still page")
    options = parser.parse_args()

    from arteleop.ar_features import OperatorView, ViewConfig
    from arteleop.scene import HeadCameraConfig, RemoteSite, SiteConfig
    from arteleop.teleop import TrialConfig, display_frames_at, trial_operator, view_assets
    from tests.instruments.browser import LLVMPIPE, SWIFTSHADER

    site = replace(SiteConfig(), camera=HeadCameraConfig(width_px=320, height_px=240))
    config = TrialConfig(seed=0, site=site)
    times = tuple(5.0 + k / 15 for k in range(30))
    with RemoteSite(config.site) as running:
        frames = display_frames_at(trial_operator(running, config), config, times, running)
        assets = view_assets(running)
    backends = {"llvmpipe (the suite's)": LLVMPIPE, "SwiftShader": SWIFTSHADER}
    runs: dict[str, list[dict[str, object]]] = {name: [] for name in backends}
    with OperatorView(ViewConfig(port=0), assets) as view:
        for _ in range(options.rounds):
            for name, args in backends.items():
                runs[name].append(measure(view, frames, args, options.windows))
                print(name, runs[name][-1], flush=True)
    rows = {name: {key: statistics.median(float(r[key]) for r in got)  # type: ignore[arg-type]
                   for key in ("still", "streaming", "page_fps", "sent_fps")}
            for name, got in runs.items()}  # fmt: skip
    first, second = rows.values()
    print("\n| measure | " + " | ".join(backends) + " | ratio |")
    print("|---|---|---|---|")
    for key, label in (("still", "still page: Chromium's cores"),
                       ("streaming", "streaming: Chromium's cores"),
                       ("page_fps", "streaming: page frames/s"),
                       ("sent_fps", "streaming: frames sent/s")):  # fmt: skip
        print(
            f"| {label} | {first[key]:.2f} | {second[key]:.2f} | {first[key] / second[key]:.2f} |"
        )
    for name, got in runs.items():
        print(f"{name}: {got[0]['renderer']}")


if __name__ == "__main__":
    main()

"""Whether a page that draws fewer frames than it is sent shows an older picture, and whether
sending it fewer clouds lets it draw more: the operator's view streamed to a headless Chromium
without a GPU (Mesa's llvmpipe, the suite's browser) at 15 camera frames a second, the cloud sent
every frame, every second and every fourth (the ghost, bars and panel every frame, as the link
pacer does).

A seeded full-AR trial (seed 0) gives 45 display frames from 5 s on, at ``--camera`` (the
served default, 640x480); one tab at 1280x800. Every half second a thread reads the page's
frame count (:mod:`arteleop.ar_features.page_frames`): the read is a message the page's script
answers after every message sent before it, so its round trip is how long the page leaves what
it is sent waiting. It grows from read to read if the page falls behind; it stays near one of
the page's frames if the page keeps up and only draws less often. The page's frames a second
come from the counts. Medians over ``--rounds``, the intervals in turn each round, with their
ratios to the cloud sent every frame (the stream a fast link gets); a still page's beside them.

    python benchmarks/bench_starved_page.py [--camera 640x480] [--rounds 2] [--seconds 12]
"""

from __future__ import annotations

import argparse
import statistics
import sys
import threading
import time
from dataclasses import replace
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))  # the checkout's tests/instruments

from bench_browser_gl import newest_client  # noqa: E402  (a sibling script)

READ_EVERY_S = 0.5
CAMERA_HZ = 15.0
INTERVALS = (1, 2, 4)


def read_while(
    client, stop: threading.Event
) -> tuple[threading.Thread, list[tuple[float, object]]]:
    """A thread that reads the page's count every :data:`READ_EVERY_S` until ``stop``, and the
    list it fills: each count with its read's round trip (s)."""
    from arteleop.ar_features.page_frames import read_count

    reads: list[tuple[float, object]] = []

    def loop() -> None:
        while not stop.is_set():
            start = time.monotonic()
            count = read_count(client)
            reads.append((time.monotonic() - start, count))
            stop.wait(READ_EVERY_S)

    thread = threading.Thread(target=loop, daemon=True)
    thread.start()
    return thread, reads


def window(view, client, frames, interval: int | None, seconds: float) -> dict[str, float]:
    """``seconds`` of the view shown still (``interval`` None) or streaming with the cloud every
    ``interval`` camera frames: frames sent and drawn a second, the reads' round trips."""
    from arteleop.ar_features.page_frames import frames_between

    stop = threading.Event()
    reader, reads = read_while(client, stop)
    start, sent = time.monotonic(), 0
    while (now := time.monotonic()) - start < seconds:
        if interval is None:
            time.sleep(0.1)
            continue
        view.cloud.interval = interval  # as the link pacer sets it before each frame
        view.show(frames[sent % len(frames)])
        sent += 1
        time.sleep(max(0.0, start + sent / CAMERA_HZ - time.monotonic()))
    stop.set()
    reader.join()
    trips = [trip for trip, _ in reads]
    counts = [count for _, count in reads if count is not None]
    _, page_fps = frames_between(counts[0], counts[-1]) if len(counts) > 1 else (None, float("nan"))
    half = trips[len(trips) // 2 :]
    return {"sent_fps": sent / (now - start), "page_fps": page_fps,
            "trip_s": statistics.median(trips), "trip_late_s": statistics.median(half),
            "trip_max_s": max(trips)}  # fmt: skip


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--camera", default="640x480", help="the head camera's WxH in pixels")
    parser.add_argument("--rounds", type=int, default=2, help="each interval this many times")
    parser.add_argument("--seconds", type=float, default=12.0, help="each window's length (s)")
    options = parser.parse_args()
    width_px, height_px = (int(n) for n in options.camera.split("x"))

    from arteleop.ar_features import OperatorView, ViewConfig
    from arteleop.ar_features.page_frames import frame_counter_html
    from arteleop.scene import HeadCameraConfig, RemoteSite, SiteConfig
    from arteleop.teleop import TrialConfig, display_frames_at, trial_operator, view_assets
    from tests.instruments.browser import LLVMPIPE, chromium

    camera = HeadCameraConfig(width_px=width_px, height_px=height_px)
    config = TrialConfig(seed=0, site=replace(SiteConfig(), camera=camera))
    times = tuple(5.0 + k / CAMERA_HZ for k in range(45))
    with RemoteSite(config.site) as running:
        frames = display_frames_at(trial_operator(running, config), config, times, running)
        assets = view_assets(running)
    runs: dict[int | None, list[dict[str, float]]] = {k: [] for k in (None, *INTERVALS)}
    with OperatorView(ViewConfig(port=0), assets) as view:
        view.show_still(frames[0])
        with chromium(LLVMPIPE) as launched:
            launched.open(view.url, for_pictures=False)
            client = newest_client(view)
            client.gui.add_html(frame_counter_html(client.client_id))
            time.sleep(5.0)
            for _ in range(options.rounds):
                for interval in runs:
                    runs[interval].append(window(view, client, frames, interval, options.seconds))
                    print(interval, runs[interval][-1], flush=True)
                    view.show_still(frames[0])
                    time.sleep(3.0)
    print(f"\ncamera {options.camera}, {CAMERA_HZ:.0f} camera frames a second, medians of "
          f"{options.rounds} windows of {options.seconds:.0f} s\n")  # fmt: skip
    rows = {k: {key: statistics.median(r[key] for r in got) for key in got[0]}
            for k, got in runs.items()}  # fmt: skip
    base = rows[1]  # the cloud every frame: the stream as a fast link gets it
    print("| cloud sent | frames sent/s | page frames/s | ratio | read round trip (s) | ratio "
          "| its second half (s) | its longest (s) |\n|---|---|---|---|---|---|---|---|")  # fmt: skip
    for interval, row in rows.items():
        label = "none (still page)" if interval is None else f"every {interval} frame(s)"
        print(f"| {label} | {row['sent_fps']:.1f} | {row['page_fps']:.1f} "
              f"| {row['page_fps'] / base['page_fps']:.2f} | {row['trip_s']:.3f} "
              f"| {row['trip_s'] / base['trip_s']:.2f} | {row['trip_late_s']:.3f} "
              f"| {row['trip_max_s']:.3f} |")  # fmt: skip


if __name__ == "__main__":
    main()

"""The operator's view: what each layer costs per frame, and whether the view keeps up in real time.

1. Per-frame cost of each layer's update and of the whole ``OperatorView.show`` (median, p95),
   at 320x240 and 640x480, with one websocket client connected (``ViewProbe``), on the frame
   of seed 0, 8 s into the trial, its arm moved a little each time so that every update sends.
2. Real-time trials with the camera at 30 Hz, all layers and three clients connected: the
   OpenGL camera against TinyRenderer (the baseline, at 640x480), at both sizes. Latency from an operator sample to the first
   display update that shows it (median, p95, and its median over the first and the last 10 s:
   no growing lag), display updates per second, and how far the simulation fell behind real
   time by the end.

3. With ``--baseline REF``: the OpenGL 640x480 run of part 2 for this checkout and for a git
   worktree of REF, one after the other (each needs both cores), ``--rounds`` times with the
   order swapped each round: this machine's speed drifts by 10-20 % from one minute to the next.

    python benchmarks/bench_view.py [--seconds 60] [--parts layers,realtime]
        [--baseline REF --rounds 3]
"""

from __future__ import annotations

from arteleop import blas_kernel  # noqa: F401  (first: it picks numpy's BLAS kernel)

# isort: split
import os

os.environ.setdefault("OMP_NUM_THREADS", "1")

import argparse
import contextlib
import json
import subprocess
import sys
import time
from dataclasses import replace
from pathlib import Path

import numpy as np
from bench_speed import ROOT, baseline_tree  # benchmarks/, the script's folder

from arteleop.ar_features import DisplayFrame, OperatorView, ViewConfig
from arteleop.scene import HeadCameraConfig, RemoteSite, SiteConfig
from arteleop.teleop import TrialConfig, display_frame_at, run_trial, trial_operator, view_assets

sys.path.insert(0, str(ROOT))  # the checkout's tests/instruments
from tests.instruments.view_probe import ViewProbe

SIZES = ((320, 240), (640, 480))
CLIENTS = 3


def layer_costs(repeats: int) -> None:
    print("\n## Per-frame cost of each layer (ms), one client connected\n")
    print("| camera | layer | median | p95 |")
    print("| --- | --- | ---: | ---: |")
    rng = np.random.default_rng(0)
    for w, h in SIZES:
        config = TrialConfig(
            seed=0, site=SiteConfig(camera=HeadCameraConfig(width_px=w, height_px=h))
        )
        with RemoteSite(config.site) as site:
            frame = display_frame_at(trial_operator(site, config), config, 8.0, site)
            assets = view_assets(site)
        with OperatorView(ViewConfig(port=0), assets) as view, ViewProbe(view.url):
            time.sleep(0.3)
            frames = [
                replace(frame, arm_q_rad=frame.arm_q_rad + rng.normal(0, 1e-3, 7))
                for _ in range(repeats)
            ]
            for layer in view.layers:
                cost = []
                for f in frames:
                    t0 = time.perf_counter()
                    layer.draw(f)
                    view.server.flush()
                    cost.append(time.perf_counter() - t0)
                name = type(layer).__name__
                print(
                    f"| {w}x{h} | {name} | {np.median(cost) * 1e3:.2f} | {np.percentile(cost, 95) * 1e3:.2f} |"
                )
            total = []
            for f in frames:
                t0 = time.perf_counter()
                view.show(f)
                total.append(time.perf_counter() - t0)
            print(
                f"| {w}x{h} | all (OperatorView.show) | {np.median(total) * 1e3:.2f} | {np.percentile(total, 95) * 1e3:.2f} |"
            )


class _CountingDisplay:
    def __init__(self, view: OperatorView) -> None:
        self.view = view
        self.shown_s: list[float] = []

    def show(self, frame: DisplayFrame) -> None:
        self.view.show(frame)
        self.shown_s.append(time.perf_counter())


REALTIME_RUNS = (
    ("tiny", 640, 480),
    ("gl", 640, 480),
    ("tiny", 320, 240),
    ("gl", 320, 240),
)
"""(renderer, width, height) of the real-time rows; the first is the baseline."""


def realtime_run(renderer: str, w: int, h: int, seconds: float) -> dict[str, object]:
    """One real-time full-AR trial of ``seconds`` with all layers and :data:`CLIENTS` clients:
    the latencies (ms), display updates per second, the lag behind real time at the end (ms),
    and the display's stage medians (ms)."""
    camera = HeadCameraConfig(width_px=w, height_px=h, renderer=renderer)
    config = TrialConfig(
        modality="full", seed=0, timeout_s=seconds, realtime=True, render_camera=True,
        site=SiteConfig(camera=camera),
    )  # fmt: skip
    with RemoteSite(config.site) as site, contextlib.ExitStack() as stack:
        view = stack.enter_context(OperatorView(ViewConfig(port=0), view_assets(site)))
        for _ in range(CLIENTS):
            stack.enter_context(ViewProbe(view.url))
        display = _CountingDisplay(view)
        site.start_render_process()
        t0 = time.perf_counter()
        result = run_trial(trial_operator(site, config), config, site, display)
        behind_ms = (time.perf_counter() - t0 - result.duration_s) * 1000
    stages = {s.stage: s.latency_median_ms for s in result.stages}
    return {
        "latency_ms": result.latency_wall_ms.tolist(),
        "duration_s": result.duration_s,
        "rate_hz": len(display.shown_s) / (display.shown_s[-1] - display.shown_s[0]),
        "behind_ms": behind_ms,
        **{f"{stage}_ms": stages.get(stage, float("nan"))
           for stage in ("camera", "point_cloud", "display")},
    }  # fmt: skip


def realtime(seconds: float) -> None:
    print(
        f"\n## Real time, all layers, camera at 30 Hz, {seconds:.0f} s, {CLIENTS} clients "
        "connected; the camera renders in its own process\n"
    )
    print(
        "| camera | latency median (ms) | p95 (ms) | median first 10 s | median last 10 s "
        "| updates / s | behind real time at the end (ms) | median / TinyRenderer 640x480 |"
    )
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    baseline = None
    for renderer, w, h in REALTIME_RUNS:
        run = realtime_run(renderer, w, h, seconds)
        lat = np.array(run["latency_ms"])
        n10 = max(1, round(len(lat) * 10 / run["duration_s"]))
        median = float(np.median(lat))
        baseline = baseline or median
        name = {"tiny": "TinyRenderer", "gl": "OpenGL"}[renderer]
        print(
            f"| {name} {w}x{h} | {median:.1f} | {np.percentile(lat, 95):.1f} "
            f"| {np.median(lat[:n10]):.1f} | {np.median(lat[-n10:]):.1f} | {run['rate_hz']:.1f} "
            f"| {run['behind_ms']:.0f} | {median / baseline:.2f} |"
        )


def against_baseline(ref: str, rounds: int, seconds: float) -> None:
    """The OpenGL 640x480 real-time run of this checkout and of a worktree of ``ref``, one
    after the other (each needs both cores), ``rounds`` times, the order swapped each round."""
    trees = {"this checkout": ROOT, f"baseline {ref}": baseline_tree(ref)}
    print(
        f"\n## Real time at 640x480 (OpenGL), {seconds:.0f} s, {CLIENTS} clients, against "
        f"{ref}: {rounds} rounds, alternating\n"
    )
    runs: dict[str, list[dict]] = {name: [] for name in trees}
    for r in range(rounds):
        for name in list(trees)[:: 1 if r % 2 == 0 else -1]:
            env = {**os.environ, "PYTHONPATH": str(trees[name]), "OMP_NUM_THREADS": "1"}
            out = subprocess.run(
                [sys.executable, str(Path(__file__).resolve()), "--worker",
                 "--seconds", str(seconds)],
                cwd=trees[name], env=env, capture_output=True, text=True,
            )  # fmt: skip
            if out.returncode != 0:
                sys.exit(f"{name}: the run failed (exit {out.returncode}):\n{out.stderr[-2000:]}")
            run = json.loads(out.stdout.splitlines()[-1])
            if r == 0:
                print(f"{name}: arteleop from {run['package']}")
            runs[name].append(run)
    print(
        "| code | latency median (ms), per round | median of rounds | p95 (ms) | updates / s "
        "| camera (ms) | point cloud (ms) | display (ms) | median / baseline |"
    )
    print("| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    base = float(np.median([np.median(r["latency_ms"]) for r in runs[f"baseline {ref}"]]))
    for name, rows in runs.items():
        medians = [float(np.median(r["latency_ms"])) for r in rows]
        m = float(np.median(medians))

        def over(key: str, rows: list[dict] = rows) -> float:
            return float(np.median([r[key] for r in rows]))

        p95 = float(np.median([np.percentile(r["latency_ms"], 95) for r in rows]))
        print(
            f"| {name} | {', '.join(f'{x:.1f}' for x in medians)} | {m:.1f} | {p95:.1f} "
            f"| {over('rate_hz'):.1f} | {over('camera_ms'):.1f} | {over('point_cloud_ms'):.1f} "
            f"| {over('display_ms'):.1f} | {m / base:.2f} |"
        )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=60.0)
    parser.add_argument("--repeats", type=int, default=200)
    parser.add_argument("--parts", default="layers,realtime")
    parser.add_argument("--baseline", help="also: real time at 640x480 against this commit")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--worker", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.worker:  # one run for against_baseline, in the tree on PYTHONPATH
        import arteleop

        run = realtime_run("gl", 640, 480, args.seconds)
        print(json.dumps({"package": str(Path(arteleop.__file__).parent), **run}))
        return
    parts = args.parts.split(",")
    if "layers" in parts:
        layer_costs(args.repeats)
    if "realtime" in parts:
        realtime(args.seconds)
    if args.baseline:
        against_baseline(args.baseline, args.rounds, args.seconds)


if __name__ == "__main__":
    main()

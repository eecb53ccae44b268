"""The head camera's cost per frame on one core: render, depth and noise, point cloud.

Side by side in this script, frame by frame: TinyRenderer's full render, every body drawn every
frame (the baseline); TinyRenderer in two layers (what ``RenderWorld`` does with
``renderer="tiny"``); and OpenGL (``renderer="gl"``, Mesa's llvmpipe here). The floor row is
TinyRenderer drawing an empty world at the same size and camera, what any of its frames costs
before anything is drawn. The frames are states of a full-AR trial, spread
evenly over it, so the arm is seen at rest, reaching, carrying and returning.

    python benchmarks/bench_camera.py [--frames 40]
"""

from __future__ import annotations

from arteleop import blas_kernel  # noqa: F401  (first: it picks numpy's BLAS kernel)

# isort: split
import os

os.environ.setdefault("OMP_NUM_THREADS", "1")  # before numpy/open3d load their thread pools

import argparse
import statistics
import time
from dataclasses import replace

import numpy as np
import pybullet as p
from pybullet_utils.bullet_client import BulletClient

from arteleop.robot.native_output import native_stdout_silenced
from arteleop.scene import HeadCameraConfig, RemoteSite, SiteConfig, frame_to_point_cloud
from arteleop.scene.camera import render
from arteleop.scene.render_world import SceneState
from arteleop.teleop import TrialConfig, run_trial, trial_operator
from arteleop.teleop.display_feed import CLOUD_STRIDE


def trial_states(site: RemoteSite, frames: int) -> list[SceneState]:
    """``frames`` scene states spread evenly over a full-AR trial (seed 0): the arm at rest,
    reaching, holding the bowl over the table and back, as a real run shows it."""
    config = TrialConfig(modality="full", seed=0)
    states: list[tuple[float, SceneState]] = []
    run_trial(trial_operator(site, config), config, site,
              progress=lambda status: states.append((status.time_s, site.scene_state())))  # fmt: skip
    picks = np.linspace(0, len(states) - 1, frames).round().astype(int)
    return [states[i][1] for i in picks]


def measure(
    site: RemoteSite, gl_site: RemoteSite, states: list[SceneState], empty: BulletClient
) -> dict[str, dict[str, float]]:
    """Median ms per stage, for the baseline, the layers, OpenGL and an empty world (the
    floor), interleaved frame by frame."""
    world, camera = site.render_world, site.camera
    request = camera.request()
    renders = {
        "baseline": lambda: render(world.client, request),
        "layers": lambda: world.render(request),
        "gl": lambda: gl_site.render_world.render(request),
        "floor": lambda: render(empty, request),
    }
    times: dict[str, dict[str, list[float]]] = {
        k: {"render": [], "depth": [], "cloud": [], "total": []} for k in renders
    }
    for k, state in enumerate(states):
        world.sync(state)
        gl_site.render_world.sync(state)
        for name, draw in renders.items():
            t0 = time.perf_counter()
            raw = draw()
            t1 = time.perf_counter()
            frame = camera.frame(raw, k / 30)
            t2 = time.perf_counter()
            frame_to_point_cloud(frame, CLOUD_STRIDE)
            t3 = time.perf_counter()
            stages = times[name]
            for stage, dt in (("render", t1 - t0), ("depth", t2 - t1), ("cloud", t3 - t2),
                              ("total", t3 - t0)):  # fmt: skip
                stages[stage].append(dt * 1000)
    return {k: {s: statistics.median(v) for s, v in st.items()} for k, st in times.items()}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--frames", type=int, default=40)
    args = parser.parse_args()
    if hasattr(os, "sched_setaffinity"):
        os.sched_setaffinity(0, {min(os.sched_getaffinity(0))})
    print(
        f"Head camera on one core: median ms per frame over {args.frames} frames of a full-AR "
        f"trial; the cloud keeps every {CLOUD_STRIDE}nd row and column, as the display's does.\n"
    )
    print(
        "| image | stage | baseline: TinyRenderer full (ms) | TinyRenderer layers (ms) "
        "| OpenGL (ms) | baseline / layers | baseline / OpenGL |"
    )
    print("| --- | --- | ---: | ---: | ---: | ---: | ---: |")
    for w, h in ((640, 480), (320, 240)):
        camera = HeadCameraConfig(width_px=w, height_px=h, renderer="tiny")
        with native_stdout_silenced():  # PyBullet prints its argv on connecting
            empty = BulletClient(connection_mode=p.DIRECT)
        with (
            RemoteSite(SiteConfig(camera=camera)) as site,
            RemoteSite(SiteConfig(camera=replace(camera, renderer="gl"))) as gl_site,
        ):
            result = measure(site, gl_site, trial_states(site, args.frames), empty)
        empty.disconnect()
        base, layers, gl = result["baseline"], result["layers"], result["gl"]
        for stage in ("render", "depth", "cloud", "total"):
            label = "render + depth + cloud" if stage == "total" else stage
            print(
                f"| {w}x{h} | {label} | {base[stage]:.1f} | {layers[stage]:.1f} "
                f"| {gl[stage]:.1f} | {base[stage] / layers[stage]:.2f} "
                f"| {base[stage] / gl[stage]:.2f} |"
            )
        print(
            f"| {w}x{h} | frames per second | {1000 / base['total']:.1f} "
            f"| {1000 / layers['total']:.1f} | {1000 / gl['total']:.1f} "
            f"| {base['total'] / layers['total']:.2f} | {base['total'] / gl['total']:.2f} |"
        )
        print(
            f"| {w}x{h} | floor: TinyRenderer, empty world | {result['floor']['render']:.1f} "
            "| | | | |"
        )


if __name__ == "__main__":
    main()

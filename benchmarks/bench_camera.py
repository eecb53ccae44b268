"""The head camera's cost per frame on one core: render, depth and noise, point cloud.

Baseline, side by side in this script: the full render, every body drawn every frame (what
``RenderWorld`` did before it drew in layers). The arm moves between frames, along a path over
the table, so neither side renders the same state twice.

    python benchmarks/bench_camera.py [--frames 40]
"""

from __future__ import annotations

import os

os.environ.setdefault("OMP_NUM_THREADS", "1")  # before numpy/open3d load their thread pools

import argparse
import statistics
import time

import numpy as np

from arteleop.robot import RIGHT_ARM_JOINTS
from arteleop.scene import HeadCameraConfig, RemoteSite, SiteConfig, frame_to_point_cloud
from arteleop.scene.camera import render
from arteleop.teleop.display_feed import CLOUD_STRIDE
from arteleop.transforms import make_transform


def arm_path(site: RemoteSite, frames: int) -> list[dict[str, float]]:
    """Joint positions with the gripper on a circle 20 cm above the table, pointing down."""
    ws = site.config.workspace
    centre = ws.on_table(((ws.start_m + ws.target_m) / 2)[:2]) + (0.0, 0.0, 0.2)
    path = []
    for k in range(frames):
        angle = 2 * np.pi * k / frames
        above = centre + 0.12 * np.array([np.cos(angle), np.sin(angle), 0.0])
        target = make_transform(np.diag([1.0, -1.0, -1.0]), above)
        for _ in range(8):  # PyBullet's IK improves from its own answer
            q = site.robot.pybullet_ik(target)
            site.robot.set_joint_positions(dict(zip(RIGHT_ARM_JOINTS, q, strict=True)))
        path.append(dict(zip(RIGHT_ARM_JOINTS, q.tolist(), strict=True)))
    return path


def measure(site: RemoteSite, path: list[dict[str, float]]) -> dict[str, dict[str, float]]:
    """Median ms per stage, for the baseline and the layers, interleaved frame by frame."""
    world, camera = site.render_world, site.camera
    request = camera.request()
    renders = {
        "baseline": lambda: render(world.client, request),
        "layers": lambda: world.render(request),
    }
    times: dict[str, dict[str, list[float]]] = {
        k: {"render": [], "depth": [], "cloud": [], "total": []} for k in renders
    }
    for k, positions in enumerate(path):
        site.robot.set_joint_positions(positions)
        world.sync(site.scene_state())
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
        f"Head camera on one core: median ms per frame over {args.frames} frames of a moving "
        f"arm; the cloud keeps every {CLOUD_STRIDE}nd row and column, as the display's does.\n"
    )
    print("| image | stage | baseline: full render (ms) | layers (ms) | baseline / layers |")
    print("| --- | --- | ---: | ---: | ---: |")
    for w, h in ((640, 480), (320, 240)):
        config = SiteConfig(camera=HeadCameraConfig(width_px=w, height_px=h))
        with RemoteSite(config) as site:
            result = measure(site, arm_path(site, args.frames))
        base, ours = result["baseline"], result["layers"]
        for stage in ("render", "depth", "cloud", "total"):
            label = "render + depth + cloud" if stage == "total" else stage
            print(
                f"| {w}x{h} | {label} | {base[stage]:.1f} | {ours[stage]:.1f} "
                f"| {base[stage] / ours[stage]:.2f} |"
            )
        print(
            f"| {w}x{h} | frames per second | {1000 / base['total']:.1f} "
            f"| {1000 / ours['total']:.1f} | {base['total'] / ours['total']:.2f} |"
        )


if __name__ == "__main__":
    main()

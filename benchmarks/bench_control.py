"""Control-loop measurements (issue: teleoperation control), on one core.

1. IK side by side: mink (ours) and PyBullet's calculateInverseKinematics (baseline) on the same
   reachable targets, from the same seed posture: position and orientation error, time per target.
2. Per-stage timing and batch speed of a full synthetic trial without camera rendering.
3. End-to-end latency in real-time mode with the camera rendering at 30 Hz.

    python benchmarks/bench_control.py [--targets 1000] [--latency-seconds 20]
"""

from __future__ import annotations

import os

os.environ.setdefault("OMP_NUM_THREADS", "1")

import argparse
import time

import numpy as np
from scipy.spatial.transform import Rotation

from arteleop.robot import GRIPPER_FRAME, RIGHT_ARM_JOINTS, WORK_POSTURE
from arteleop.robot.ik import ArmIK
from arteleop.scene import HeadCameraConfig, RemoteSite, SiteConfig
from arteleop.teleop import TrialConfig, TrialResult, run_trial, synthetic_source


def ik_side_by_side(n: int) -> None:
    site = RemoteSite()
    kin, robot = site.kinematics, site.robot
    lim = kin.limits(RIGHT_ARM_JOINTS)
    ik = ArmIK(site.description.urdf_path, lim, WORK_POSTURE)
    rng = np.random.default_rng(0)
    rows = {"mink": [], "pybullet": []}
    for _ in range(n):
        q = rng.uniform(lim.lower, lim.upper)
        T = kin.frame_transform(dict(zip(RIGHT_ARM_JOINTS, q, strict=True)), GRIPPER_FRAME)
        # mink, converged offline solve from the working posture
        ik.reset(WORK_POSTURE)
        ik.set_target(T)
        t0 = time.perf_counter()
        r = ik.solve()
        rows["mink"].append((r.position_error_m, r.orientation_error_rad, time.perf_counter() - t0))
        # PyBullet from the same posture
        robot.set_joint_positions(dict(zip(RIGHT_ARM_JOINTS, WORK_POSTURE, strict=True)))
        t0 = time.perf_counter()
        q_pb = robot.pybullet_ik(T)
        dt = time.perf_counter() - t0
        T_pb = kin.frame_transform(dict(zip(RIGHT_ARM_JOINTS, q_pb, strict=True)), GRIPPER_FRAME)
        rot = Rotation.from_matrix(T_pb[:3, :3].T @ T[:3, :3]).magnitude()
        rows["pybullet"].append((float(np.linalg.norm(T_pb[:3, 3] - T[:3, 3])), rot, dt))
    ik.reset(WORK_POSTURE)
    step = []
    for _ in range(2000):
        t0 = time.perf_counter()
        ik.step(0.01)
        step.append(time.perf_counter() - t0)
    site.close()
    print(f"\n## IK on {n} reachable targets from random configurations (same seed posture)\n")
    print(
        "| solver | position error median (mm) | p95 (mm) | orientation error median (deg) | time per target median (ms) |"
    )
    print("| --- | ---: | ---: | ---: | ---: |")
    for name, label in (
        ("pybullet", "PyBullet calculateInverseKinematics (baseline)"),
        ("mink", "mink, converged (ours)"),
    ):
        a = np.array(rows[name])
        print(
            f"| {label} | {np.median(a[:, 0]) * 1e3:.3f} | {np.percentile(a[:, 0], 95) * 1e3:.1f} | {np.degrees(np.median(a[:, 1])):.3f} | {np.median(a[:, 2]) * 1e3:.2f} |"
        )
    print(
        f"\nmink, one IK step per 10 ms control tick: median {np.median(step) * 1e3:.3f} ms, p99 {np.percentile(step, 99) * 1e3:.3f} ms"
    )


def trial_timing(seconds: float) -> None:
    config = TrialConfig(modality="full", seed=0, timeout_s=seconds)
    with RemoteSite(config.site) as site:
        t0 = time.perf_counter()
        result = run_trial(synthetic_source(site, config), config, site)
        wall = time.perf_counter() - t0
    print(
        f"\n## One synthetic full-AR trial in batch mode, no camera rendering ({result.outcome}, {result.duration_s:.1f} s simulated)\n"
    )
    print(f"batch speed: {result.duration_s / wall:.1f} simulated seconds per wall second\n")
    _stages(result)


def latency(seconds: float) -> None:
    print("\n## End-to-end latency, real-time mode, camera rendering at 30 Hz\n")
    print(
        "| camera | sample to first frame showing it, median (ms) | p95 (ms) | + render and point cloud, median (ms) | real-time lag at end (ms) |"
    )
    print("| --- | ---: | ---: | ---: | ---: |")
    for w, h in ((320, 240), (640, 480)):
        site_cfg = SiteConfig(camera=HeadCameraConfig(width_px=w, height_px=h))
        config = TrialConfig(
            modality="full",
            seed=0,
            timeout_s=seconds,
            realtime=True,
            render_camera=True,
            site=site_cfg,
        )
        with RemoteSite(config.site) as site:
            t0 = time.perf_counter()
            result = run_trial(synthetic_source(site, config), config, site)
            lag = (time.perf_counter() - t0 - result.duration_s) * 1000
        stages = {s.stage: s for s in result.stages}
        processing = stages["camera"].latency_median_ms + stages["point_cloud"].latency_median_ms
        lat = result.latency_sim_ms
        print(
            f"| {w}x{h} | {np.median(lat):.1f} | {np.percentile(lat, 95):.1f} | {np.median(lat) + processing:.1f} | {lag:.0f} |"
        )


def _stages(result: TrialResult) -> None:
    print(
        "| stage | rounds | service median (ms) | service p95 (ms) | latency median (us) | latency p99 (us) |"
    )
    print("| --- | ---: | ---: | ---: | ---: | ---: |")
    for s in result.stages:
        print(
            f"| {s.stage} | {s.rounds} | {s.service_median_ms:.3f} | {s.service_p95_ms:.3f} | {s.latency_median_ms * 1e3:.0f} | {s.latency_p99_ms * 1e3:.0f} |"
        )
    print(
        "\nmapping_ik is the control tick: mapping, one IK step, the trajectory's new target, the gripper command."
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--targets", type=int, default=1000)
    parser.add_argument("--trial-seconds", type=float, default=120.0)
    parser.add_argument("--latency-seconds", type=float, default=20.0)
    parser.add_argument("--parts", default="ik,trial,latency", help="comma-separated subset")
    args = parser.parse_args()
    if hasattr(os, "sched_setaffinity"):
        os.sched_setaffinity(0, {min(os.sched_getaffinity(0))})
    parts = set(args.parts.split(","))
    if "ik" in parts:
        ik_side_by_side(args.targets)
    if "trial" in parts:
        trial_timing(args.trial_seconds)
    if "latency" in parts:
        latency(args.latency_seconds)


if __name__ == "__main__":
    main()

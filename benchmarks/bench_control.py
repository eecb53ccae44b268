"""Control-loop measurements (issue: teleoperation control), on one core.

1. IK side by side: mink (ours) and PyBullet's calculateInverseKinematics (baseline) on the same
   reachable targets, from the same seed posture: position and orientation error, time per target.
2. Batch speed of seeded full synthetic trials without camera rendering, against the same trials
   with every joint of Baxter simulated (baseline), and where each simulated second goes.
3. End-to-end latency in real-time mode with the camera rendering at 30 Hz, to the viser view
   and on to a connected websocket client.

    python benchmarks/bench_control.py [--targets 1000] [--seeds 5] [--latency-seconds 20]
        [--parts ik,trial,latency]
"""

from __future__ import annotations

from arteleop import blas_kernel  # noqa: F401  (first: it picks numpy's BLAS kernel)

# isort: split
import os

os.environ.setdefault("OMP_NUM_THREADS", "1")

import argparse
import sys
import time

import mink
import numpy as np
from bench_speed import ROOT, record_commands, replay_commands  # benchmarks/, the script's folder
from scipy.spatial.transform import Rotation

from arteleop.ar_features import DisplayFrame, OperatorView, ViewConfig
from arteleop.robot import GRIPPER_FRAME, RIGHT_ARM_JOINTS, WORK_POSTURE
from arteleop.robot.ik import ArmIK, IKConfig
from arteleop.scene import HeadCameraConfig, RemoteSite, SiteConfig
from arteleop.teleop import TrialConfig, TrialResult, run_trial, trial_operator

sys.path.insert(0, str(ROOT))  # the checkout's tests/instruments
from tests.instruments.view_probe import ViewProbe


def ik_side_by_side(n: int) -> None:
    site = RemoteSite()
    kin, robot = site.kinematics, site.robot
    lim = kin.limits(RIGHT_ARM_JOINTS)
    ik = ArmIK(site.description.urdf_path, lim, WORK_POSTURE)
    rng = np.random.default_rng(0)
    rows = {"mink": [], "pybullet": []}
    for _ in range(n):
        q = rng.uniform(lim.lower, lim.upper)
        elbow = RIGHT_ARM_JOINTS.index("right_e1")
        q[elbow] = max(q[elbow], IKConfig().elbow_min_bend_rad)  # the IK keeps it off straight
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
    # One QP solve and integration each, interleaved so both see the same machine: ArmIK's
    # (mink's rows to daqp directly) against mink's own solve_ik (through qpsolvers) on a twin
    # arm; ArmIK.step adds the same error bookkeeping to either.
    twin = ArmIK(site.description.urdf_path, lim, WORK_POSTURE)
    T_far = kin.frame_transform(dict(zip(RIGHT_ARM_JOINTS, WORK_POSTURE, strict=True)),
                                GRIPPER_FRAME)  # fmt: skip
    T_far[:3, 3] += [0.1, -0.1, -0.1]
    for arm in (ik, twin):
        arm.reset(WORK_POSTURE)
        arm.set_target(T_far)
    step: dict[str, list[float]] = {"ours": [], "mink": []}
    for _ in range(2000):
        t0 = time.perf_counter()
        ik.configuration.integrate_inplace(ik._velocity(0.01), 0.01)
        t1 = time.perf_counter()
        v = mink.solve_ik(twin.configuration, twin.tasks, 0.01, "daqp", 1e-6, limits=twin.limits)
        twin.configuration.integrate_inplace(v, 0.01)
        t2 = time.perf_counter()
        step["ours"].append(t1 - t0)
        step["mink"].append(t2 - t1)
    same = bool(np.array_equal(ik.configuration.q, twin.configuration.q))
    site.close()
    print(f"\n## IK on {n} reachable targets from random configurations (same seed posture)\n")
    print(
        "| solver | position error median (mm) | p95 (mm) | orientation error median (deg) "
        "| time per target median (ms) | time / baseline |"
    )
    print("| --- | ---: | ---: | ---: | ---: | ---: |")
    base_time = float(np.median(np.array(rows["pybullet"])[:, 2]))
    for name, label in (
        ("pybullet", "PyBullet calculateInverseKinematics (baseline)"),
        ("mink", "mink, converged (ours)"),
    ):
        a = np.array(rows[name])
        print(
            f"| {label} | {np.median(a[:, 0]) * 1e3:.3f} | {np.percentile(a[:, 0], 95) * 1e3:.1f} "
            f"| {np.degrees(np.median(a[:, 1])):.3f} | {np.median(a[:, 2]) * 1e3:.2f} "
            f"| {np.median(a[:, 2]) / base_time:.2f} |"
        )
    print("\n## One IK step per 10 ms control tick, 2000 ticks, interleaved\n")
    print("| step | median (us) | p99 (us) | time / baseline |")
    print("| --- | ---: | ---: | ---: |")
    base = float(np.median(step["mink"]))
    for name, label in (("mink", "mink.solve_ik via qpsolvers (baseline)"),
                        ("ours", "ArmIK: mink's rows to daqp")):  # fmt: skip
        t = np.array(step[name])
        print(f"| {label} | {np.median(t) * 1e6:.0f} | {np.percentile(t, 99) * 1e6:.0f} "
              f"| {np.median(t) / base:.2f} |")  # fmt: skip
    print(f"\nSame joints after 2000 ticks, to the bit: {same}")


def trial_timing(seconds: float, seeds: int) -> None:
    """Batch speed over seeded full-AR trials, ours against the whole robot simulated."""
    setups = {
        "every joint of Baxter simulated (baseline)": SiteConfig(freeze_idle_joints=False),
        "right arm only, fixed links merged (arteleop)": SiteConfig(),
    }
    speeds: dict[str, list[float]] = {k: [] for k in setups}
    durations: dict[str, list[float]] = {k: [] for k in setups}
    kept: TrialResult | None = None
    for seed in range(seeds):
        for name, site_config in setups.items():  # interleaved, so drifts hit both alike
            config = TrialConfig(modality="full", seed=seed, timeout_s=seconds, site=site_config)
            with RemoteSite(config.site) as site:
                t0 = time.perf_counter()
                result = run_trial(trial_operator(site, config), config, site)
                wall = time.perf_counter() - t0
            speeds[name].append(result.duration_s / wall)
            durations[name].append(result.duration_s)
            if seed == 0 and site_config.freeze_idle_joints:
                kept = result
    print(f"\n## Batch speed: {seeds} seeded full-AR trials, no camera rendering, one core\n")
    print("| setup | simulated s, median | batch speed median (x) | min | max | vs baseline |")
    print("| --- | ---: | ---: | ---: | ---: | ---: |")
    base = float(np.median(next(iter(speeds.values()))))
    for name in setups:
        v = speeds[name]
        print(
            f"| {name} | {np.median(durations[name]):.1f} | {np.median(v):.1f} | {min(v):.1f} "
            f"| {max(v):.1f} | {np.median(v) / base:.2f} |"
        )
    assert kept is not None
    print(f"\n## Where a simulated second goes (arteleop, seed 0, {kept.outcome.value})\n")
    _stages(kept)
    ceiling = physics_replay(seconds)
    print(
        f"\nCeiling: PyBullet alone, replaying seed 0's arm and gripper commands step by step "
        f"(no operator, no control, no Python beyond the replay loop): {ceiling:.1f}x real time."
    )


def physics_replay(seconds: float) -> float:
    """Batch speed of the physics alone: record a trial's commands, replay them on a new site."""
    config = TrialConfig(modality="full", seed=0, timeout_s=seconds)
    with RemoteSite(config.site) as site:
        events = record_commands(site)
        duration_s = run_trial(trial_operator(site, config), config, site).duration_s
    with RemoteSite(config.site) as site:
        return duration_s / replay_commands(site, events)


class _TimedDisplay:
    """The operator's view, noting when each frame was handed to it."""

    def __init__(self, view: OperatorView) -> None:
        self.view = view
        self.shown_s: list[float] = []

    def show(self, frame: DisplayFrame) -> None:
        self.shown_s.append(time.perf_counter())
        self.view.show(frame)


ORIGINAL_LATENCY_MS = 89.0
"""End-to-end latency the original system measured (docs/explanation/study.md), the reference for this table."""


def latency(seconds: float) -> None:
    print(
        "\n## End-to-end latency, real-time mode, camera rendering at 30 Hz, viser view, "
        "both cores\n"
    )
    print(
        "| camera | sample to frame capture, simulated, median (ms) | sample to display update, "
        "wall clock, median (ms) | p95 (ms) | show call to a connected client, median (ms) "
        "| median / original system's 89 ms | frames shown / skipped | real-time lag at end (ms) |"
    )
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for w, h in ((320, 240), (640, 480)):
        site_cfg = SiteConfig(camera=HeadCameraConfig(width_px=w, height_px=h))
        config = TrialConfig(
            modality="full", seed=0, timeout_s=seconds, realtime=True, render_camera=True,
            site=site_cfg,
        )  # fmt: skip
        with (
            RemoteSite(config.site) as site,
            OperatorView(ViewConfig(port=0)) as view,
            ViewProbe(view.url) as client,
        ):
            display = _TimedDisplay(view)
            site.start_render_process()  # a few seconds, not part of the run
            t0 = time.perf_counter()
            result = run_trial(trial_operator(site, config), config, site, display)
            lag = (time.perf_counter() - t0 - result.duration_s) * 1000
            time.sleep(0.5)
            clouds = client.messages(min_bytes=20_000)
        # Each update is one large message, in order; pair them up.
        delivery = [(m.time_s - s) * 1000 for m, s in zip(clouds, display.shown_s, strict=False)]
        wall = result.latency_wall_ms
        print(
            f"| {w}x{h} | {np.median(result.latency_sim_ms):.1f} | {np.median(wall):.1f} "
            f"| {np.percentile(wall, 95):.1f} | {np.median(delivery):.2f} "
            f"| {np.median(wall) / ORIGINAL_LATENCY_MS:.2f} | {len(display.shown_s)} / {result.counts['camera_frames_skipped']} | {lag:.0f} |"
        )
    print(
        "\nWall-clock latency runs from the operator sample's creation to the return of "
        "OperatorView.show for the first frame that shows it. The client column is the "
        "time from calling show to a websocket client (ViewProbe) holding the update; "
        "a browser then draws it within a display frame. Real time uses both cores: frames "
        "render in a process of their own; viser's server and the client are threads."
    )


def _stages(result: TrialResult) -> None:
    print(
        "| stage | rounds | service median (ms) | latency median (us) | latency p99 (us) "
        "| wall ms per simulated s |"
    )
    print("| --- | ---: | ---: | ---: | ---: | ---: |")
    for s in result.stages:
        print(
            f"| {s.stage} | {s.rounds} | {s.service_median_ms:.3f} | {s.latency_median_ms * 1e3:.0f} "
            f"| {s.latency_p99_ms * 1e3:.0f} | {s.latency_total_ms / result.duration_s:.1f} |"
        )
    print(
        "\ncontrol_tick is the whole robot-side tick: mapping, one IK step, the trajectory's new "
        "target and the gripper command; mapping and ik are its parts."
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--targets", type=int, default=1000)
    parser.add_argument("--trial-seconds", type=float, default=120.0)
    parser.add_argument("--seeds", type=int, default=5)
    parser.add_argument("--latency-seconds", type=float, default=20.0)
    parser.add_argument("--parts", default="ik,trial,latency", help="comma-separated subset")
    args = parser.parse_args()
    if hasattr(os, "sched_setaffinity"):
        os.sched_setaffinity(0, {min(os.sched_getaffinity(0))})
    parts = set(args.parts.split(","))
    if "ik" in parts:
        ik_side_by_side(args.targets)
    if "trial" in parts:
        trial_timing(args.trial_seconds, args.seeds)
    if "latency" in parts:
        if hasattr(os, "sched_setaffinity"):
            os.sched_setaffinity(0, range(os.cpu_count() or 1))
        latency(args.latency_seconds)


if __name__ == "__main__":
    main()

"""Whole trials, headless, and the loop's parts."""

from collections.abc import Callable
from dataclasses import replace

import numpy as np
import pytest

from arteleop.errors import ConfigurationError
from arteleop.operator import ImuErrorConfig, RecordingSource, load_recording, write_recording
from arteleop.scene import RemoteSite, RGBDFrame, SiteConfig
from arteleop.teleop import (
    LoopClock,
    LoopRates,
    NetworkConfig,
    NetworkLink,
    Outcome,
    TrialConfig,
    TrialResult,
    run_trial,
    trial_operator,
)
from tests.operator.motions import reach_and_return
from tests.parallel import run_each


def _full_trial(site_config: SiteConfig, seed: int) -> TrialResult:
    config = TrialConfig(modality="full", seed=seed, site=site_config)
    with RemoteSite(config.site) as site:
        return run_trial(trial_operator(site, config), config, site)


def test_full_ar_places_the_bowl_within_5_cm_in_5_of_6_trials(site_config: SiteConfig) -> None:
    """Six seeds keep the suite short; benchmarks/bench_trials.py runs more."""
    errors, outcomes = [], []
    for result in run_each(_full_trial, [(site_config, seed) for seed in range(6)]):
        outcomes.append(result.outcome.value)
        assert result.to_row()["colocation_error_px"] == 0.0  # a perfect registration
        # What the operator sees of the outcome: the camera frame the trial ended on.
        frame = result.final_frame
        assert frame is not None and 0 <= result.duration_s - frame.time_s < 1 / 30, frame
        errors.append(result.placement_error_true_m if result.placed else np.inf)
    within = sum(e <= 0.05 for e in errors)
    assert within >= 5, f"outcomes {outcomes}, errors (m) {np.round(errors, 3)}"


def test_same_seed_same_motion_in_batch_and_real_time(site_config: SiteConfig) -> None:
    # The same events, the same motion, and the same end, at the first base tick past the
    # timeout, whether the clock waits for the wall clock or not.
    results, arms = [], []
    for realtime in (False, True):
        config = TrialConfig(
            modality="none", seed=7, site=site_config, timeout_s=3.0, realtime=realtime,
            record_trace=True,
        )  # fmt: skip
        with RemoteSite(config.site) as site:
            results.append(run_trial(trial_operator(site, config), config, site))
            arms.append(site.observe().arm_q_rad)
    batch, live = results
    assert batch.outcome is live.outcome is Outcome.TIMEOUT
    assert batch.duration_s == live.duration_s == 3601 / 1200
    np.testing.assert_array_equal(batch.hand_m, live.hand_m)
    for column, values in batch.trace.items():
        np.testing.assert_array_equal(values, live.trace[column], err_msg=column)
    np.testing.assert_array_equal(arms[0], arms[1])


def test_recording_that_ends_mid_trial_stops_the_trial(site_config: SiteConfig, tmp_path) -> None:
    rec = reach_and_return(errors=ImuErrorConfig.ideal()).recording
    write_recording(rec, tmp_path / "r.csv")
    config = TrialConfig(site=site_config)
    result = run_trial(RecordingSource(load_recording(tmp_path / "r.csv")), config)
    assert result.outcome is Outcome.OPERATOR_STOPPED
    assert result.duration_s == pytest.approx(rec.duration_s, abs=0.05)


def test_nan_samples_hold_the_command_and_are_counted(site_config: SiteConfig) -> None:
    rec = reach_and_return(errors=ImuErrorConfig.ideal()).recording
    q = rec.sensor_quat_wxyz.copy()
    q[300:305] = np.nan  # five NaN samples (50 ms) after calibration: held, not lost
    q[400:430] = np.nan  # 300 ms: held for 100 ms, then lost
    result = run_trial(
        RecordingSource(type(rec)(rec.time_s, q, rec.grip, rec.info)), TrialConfig(site=site_config)
    )
    assert result.outcome is Outcome.OPERATOR_STOPPED
    assert result.counts["held_samples"] == 5 + 10


def test_a_delay_longer_than_the_timeout_is_refused() -> None:
    with pytest.raises(
        ConfigurationError,
        match=r"network delay \(200.0 s.*longer than the trial timeout \(120.0 s\)",
    ):
        TrialConfig(network=NetworkConfig(delay_s=200.0))


def test_late_packets_never_move_the_robot_back_in_time() -> None:
    link: NetworkLink[int] = NetworkLink(
        NetworkConfig(delay_s=0.05, jitter_s=0.03), np.random.default_rng(0)
    )
    delivered = []
    for k in range(2000):
        t = k * 0.01
        link.send(t, k, t)
        delivered += [sample_time for sample_time, _ in link.receive(t)]
    assert delivered == sorted(delivered) and len(set(delivered)) == len(delivered)
    assert link.late > 0  # jitter reorders packets; the overtaken ones were dropped
    assert len(delivered) + link.late + len(link._queue) == link.sent


def test_network_delay_and_loss_statistics() -> None:
    link: NetworkLink[int] = NetworkLink(
        NetworkConfig(delay_s=0.08, loss_probability=0.1), np.random.default_rng(1)
    )
    arrivals = {}
    for k in range(5000):
        t = k * 0.01
        link.send(t, k, t)
        for sample_time, _ in link.receive(t):
            arrivals[sample_time] = t
    delays = np.array([a - s for s, a in arrivals.items()])
    assert np.allclose(delays, 0.08, atol=0.01 + 1e-9)  # delivered at the first tick after 80 ms
    assert link.lost / link.sent == pytest.approx(0.1, abs=0.015)


def test_clock_fires_each_stage_at_its_rate() -> None:
    clock = LoopClock(LoopRates())
    ticks = [clock.next() for _ in range(1200)]  # one second at the 1200 Hz base rate
    assert sum(t.control for t in ticks) == 100
    assert sum(t.physics for t in ticks) == 240
    assert sum(t.camera for t in ticks) == 30
    with pytest.raises(ConfigurationError, match="physics_hz=100: use at least 240 Hz"):
        LoopRates(physics_hz=100)


def test_clock_without_idle_ticks_yields_the_firing_ticks_and_the_first_past_its_stop() -> None:
    every = LoopClock(LoopRates())
    firing = [t for t in (every.next() for _ in range(2400)) if t.control or t.physics or t.camera]
    assert len(firing) == 2 * 320  # 100 + 240 + 30 a second, less the ticks they share
    skipping = LoopClock(LoopRates(), idle_ticks=False, stop_s=1.0)
    ticks = [skipping.next() for _ in range(len(firing) + 1)]
    past_stop = next(i for i, t in enumerate(ticks) if t.time_s > 1.0)
    assert ticks[past_stop].index == 1201  # no stage fires at it: it is there for the stop
    del ticks[past_stop]
    assert ticks == firing


def test_unknown_modality_is_refused() -> None:
    with pytest.raises(
        ConfigurationError, match=r"Unknown modality 'ar'. Valid modalities: \['none'"
    ):
        replace(TrialConfig(), modality="ar")


def test_the_trace_records_every_control_tick_as_the_site_saw_it(site_config: SiteConfig) -> None:
    from arteleop.robot import GRIPPER_FRAME, RIGHT_ARM_JOINTS, BaxterKinematics
    from arteleop.teleop import TRACE_COLUMNS

    config = TrialConfig(modality="full", seed=2, site=site_config, timeout_s=5.0,
                         record_trace=True)  # fmt: skip
    with RemoteSite(config.site) as site:
        result = run_trial(trial_operator(site, config), config, site)
        kinematics = BaxterKinematics(site.description.urdf_path)
    trace = result.trace
    assert trace is not None and list(trace) == list(TRACE_COLUMNS)
    t = trace["time_s"]
    np.testing.assert_allclose(np.diff(t), 0.01, atol=1e-9)  # 100 Hz, every tick
    assert t[0] == 0.0 and len(t) == 501
    # The actual gripper is the forward kinematics of the recorded joints, at every tick.
    for k in (0, 250, 500):
        q = {j: trace[f"{j}_rad"][k] for j in RIGHT_ARM_JOINTS}
        gripper = kinematics.frame_transforms(q, (GRIPPER_FRAME,))[0][:3, 3]
        actual = [trace[f"gripper_{a}_m"][k] for a in "xyz"]
        np.testing.assert_allclose(actual, gripper, atol=1e-6)
    # The hand is the robot side's reconstruction: what the result keeps while engaged.
    engaged = np.isin(t, result.hand_time_s)
    hand = np.column_stack([trace[f"hand_{a}_m"] for a in "xyz"])
    assert engaged.sum() > 100
    np.testing.assert_array_equal(hand[np.searchsorted(t, result.hand_time_s)], result.hand_m)
    # Before calibration nothing is known of the hand, and nothing is mapped.
    assert np.isnan(trace["hand_x_m"][0]) and np.isnan(trace["gripper_target_x_m"][0])
    quats = np.column_stack([trace[f"hand_q{c}"] for c in "wxyz"])
    np.testing.assert_allclose(np.linalg.norm(quats[~np.isnan(quats[:, 0])], axis=1), 1.0)
    # The mapped target leads the gripper that tracks it: the arm follows it about 0.2 s late
    # (docs/explanation/operator-model.md, familiar_lag_s), within a few cm of where it was then.
    target = np.column_stack([trace[f"gripper_target_{a}_m"] for a in "xyz"])
    actual = np.column_stack([trace[f"gripper_{a}_m"] for a in "xyz"])
    late = 20  # control ticks: 0.2 s
    gap = np.linalg.norm(target[:-late] - actual[late:], axis=1)[engaged[late:]]
    assert np.nanmedian(gap) < 0.03


def test_failures_are_named_by_what_had_happened() -> None:
    from arteleop.scene import BowlTracker, Workspace
    from arteleop.teleop import TaskMonitor

    ws = Workspace()
    monitor = TaskMonitor(ws, BowlTracker(ws.bowl))
    assert monitor.timed_out() is Outcome.TIMEOUT
    assert monitor.operator_stopped() is Outcome.OPERATOR_STOPPED
    monitor.grasp_attempts = 2  # closed twice, never held it
    assert monitor.operator_stopped() is Outcome.NOT_GRASPED
    monitor.grasped = True
    assert monitor.operator_stopped() is Outcome.OPERATOR_STOPPED
    monitor.released = True
    assert monitor.timed_out() is Outcome.TRACKING_LOST


def test_the_tracker_renders_only_what_its_model_sees() -> None:
    """After the release, a look at which the tracker's model sees none of the bowl is not
    rendered, and counts as a look: the next is a tracking period later, as when rendered."""
    from arteleop.scene import (
        BowlTrack,
        BowlTracker,
        CameraGeometry,
        HeadCameraConfig,
        SiteState,
        Workspace,
    )
    from arteleop.teleop import TaskMonitor
    from arteleop.teleop.task_monitor import TRACKING_PERIOD_S

    ws = Workspace()
    monitor = TaskMonitor(ws, BowlTracker(ws.bowl))
    monitor.released = True
    T_base_bowl = np.eye(4)
    T_base_bowl[:3, 3] = ws.target_m
    state = SiteState(
        time_s=0.0, arm_q_rad=np.zeros(7), gripper_closure=0.0, pads_touch_bowl=(False, False),
        T_base_bowl=T_base_bowl, bowl_speed_m_s=0.0,
        camera=CameraGeometry(HeadCameraConfig(), np.eye(4)), links={},
    )  # fmt: skip
    renders: list[float] = []

    def capture() -> RGBDFrame:
        renders.append(len(renders))
        raise _Rendered

    def sight(n: int) -> Callable[[], BowlTrack]:
        return lambda: BowlTrack(n > 0, None, n, float("nan"), "", 0.0)

    assert monitor.camera(1.0, state, capture, sight(0)) is None
    assert monitor.renders_skipped == 1 and not renders
    # Within the tracking period: no look at all, whatever the model sees.
    assert monitor.camera(1.0 + TRACKING_PERIOD_S / 2, state, capture, sight(5)) is None
    assert not renders
    with pytest.raises(_Rendered):  # the next look, with part of the bowl in sight, renders
        monitor.camera(1.0 + TRACKING_PERIOD_S, state, capture, sight(1))
    assert renders == [0] and monitor.renders_skipped == 1


class _Rendered(Exception):
    pass

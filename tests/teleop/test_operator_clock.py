"""The synthetic operator's clock: each sample carries the hand of its own time.

What the operator sees is the newest display frame that has reached it, older than the sample
by the camera period and the return link's delay. That age must inform its decisions, never the
time at which its hand is evaluated: otherwise the hand becomes a staircase at the camera rate
and a network delay delays the operator's own arm.
"""

from dataclasses import replace

import numpy as np

from arteleop.analysis import normalized_jerk
from arteleop.ar_features import DisplayFrame
from arteleop.operator import (
    ArmModel,
    CalibrationPosture,
    OperatorSource,
    PickAndPlace,
    SyntheticOperator,
    WearableSample,
)
from arteleop.operator.simulated.synthetic import CALIBRATE
from arteleop.scene import RemoteSite, SiteConfig
from arteleop.teleop import LoopRates, NetworkConfig, TrialConfig, run_trial, trial_operator
from tests.ar_features.frames import display_frame
from tests.parallel import run_each


def test_the_hand_at_a_time_does_not_depend_on_the_age_of_what_is_seen() -> None:
    """Same seed, same display content: frames 0.2 s old or fresh give the same hand."""
    task = PickAndPlace(np.zeros(3), np.array([0.3, -0.56, 0.0]))
    fresh, stale = (
        SyntheticOperator(
            task, lambda p: p, ArmModel(), CalibrationPosture(), np.random.default_rng(4)
        )
        for _ in range(2)
    )
    seen = display_frame(engaged=False)  # calibrate, align, wait to engage: no perception
    moving = steps = 0
    previous = None
    for k in range(700):
        t = k / 100
        a = fresh.step(t, replace(seen, time_s=t))
        b = stale.step(t, replace(seen, time_s=max(0.0, t - 0.2)))
        assert a.time_s == b.time_s == t
        np.testing.assert_array_equal(a.hand_m, b.hand_m)
        assert a.phase == b.phase
        if previous is not None and a.phase != CALIBRATE:
            steps += 1
            moving += not np.array_equal(a.hand_m, previous)
        previous = a.hand_m
    # Past calibration, the hand moves at every sample: a new pose each 10 ms.
    assert steps > 500 and moving == steps


class _Logged:
    """An operator source that keeps every sample and the operator's phase at it."""

    def __init__(self, source: OperatorSource) -> None:
        self.source = source
        self.arm, self.calibration = source.arm, source.calibration
        self.log: list[tuple[WearableSample, str, float | None]] = []

    def sample(self, time_s: float, view: DisplayFrame) -> WearableSample | None:
        sample = self.source.sample(time_s, view)
        op = self.source.operator  # type: ignore[attr-defined]
        if sample is not None:
            self.log.append((sample, op.phase, op.movement_start_s))
        return sample


def _run(site_config: SiteConfig, seed: int, camera_hz: int, delay_s: float, timeout_s: float):
    config = TrialConfig(
        modality="full", seed=seed, timeout_s=timeout_s, site=site_config,
        rates=LoopRates(camera_hz=camera_hz), network=NetworkConfig(delay_s=delay_s),
    )  # fmt: skip
    with RemoteSite(config.site) as site:
        source = _Logged(trial_operator(site, config))
        run_trial(source, config, site)
    return source.log


def test_a_100_hz_stream_holds_100_hand_poses_a_second_under_delay(
    site_config: SiteConfig,
) -> None:
    log = _run(site_config, seed=0, camera_hz=30, delay_s=0.2, timeout_s=9.0)
    t = np.array([s.time_s for s, _, _ in log])
    hand = np.array([s.true_hand_m for s, _, _ in log])
    np.testing.assert_allclose(t, np.arange(len(t)) / 100, atol=1e-12)  # one per control tick
    for second in range(4, 9):  # past the calibration hold, engaging and reaching
        window = hand[(t >= second) & (t < second + 1)]
        assert len(np.unique(window, axis=0)) == 100, second


def test_reach_smoothness_does_not_depend_on_the_camera_rate(site_config: SiteConfig) -> None:
    """The first reach, planned from the display, is a minimum-jerk movement with tremor.

    Before the fix its normalised jerk was 4-5 times higher at 15 Hz than at 30 Hz (the hand
    stepped at the camera rate); now the camera rate only shifts what the operator perceived,
    and so when it corrects in flight, which a trial's chaos makes differ seed by seed (over
    seeds 0-7, 15 against 30 Hz: 0.64, the rest 0.93-1.08): the ratio's median over these seeds
    within 25 % of one, none beyond a factor of 2.
    """
    seeds, rates = (0, 1, 3), (30, 15)
    logs = iter(run_each(_run, [(site_config, s, hz, 0.0, 14.0) for s in seeds for hz in rates]))
    ratios = []
    for _ in seeds:
        jerks = []
        for log in (next(logs) for _ in rates):
            first = next(start for _, phase, start in log if phase == "reach" and start)
            reach = [(s.time_s, s.true_hand_m) for s, _, start in log if start == first]
            t, hand = (np.array(v) for v in zip(*reach, strict=True))
            jerks.append(normalized_jerk(t, hand, "xyz"))
        ratios.append(jerks[1] / jerks[0])
    assert abs(np.median(ratios) - 1) < 0.25, ratios
    assert all(1 / 2 < r < 2 for r in ratios), ratios

"""The predictive ghost: where the commands already sent will put the arm, ahead of the delayed
view by the round trip."""

from __future__ import annotations

import numpy as np
import pytest

from arteleop.ar_features import DisplayFrame
from arteleop.operator import OperatorSource, WearableSample
from arteleop.scene import RemoteSite, SiteConfig
from arteleop.teleop import NetworkConfig, TrialConfig, run_trial, trial_operator

CONTROL_PERIOD_S = 0.01
CAMERA_PERIOD_S = 1 / 30


class _Scripted:
    """Records what an operator sends and sees; replays the samples sent, whatever it sees."""

    def __init__(self, source: OperatorSource, script: list[WearableSample] | None = None) -> None:
        self.source, self.arm, self.calibration = source, source.arm, source.calibration
        self.seen: list[DisplayFrame] = []
        self.sent: list[WearableSample | None] = []
        self._script = script

    def sample(self, time_s: float, view: DisplayFrame) -> WearableSample | None:
        self.seen.append(view)
        if self._script is not None:
            return self._script.pop(0) if self._script else None
        sample = self.source.sample(time_s, view)
        self.sent.append(sample)
        return sample


def _lead_s(frames: list[DisplayFrame]) -> float:
    """The shift (s, in control ticks) that best lays the predicted gripper's path onto the
    path the frames show, once the prediction has begun."""
    start = next(k for k, f in enumerate(frames) if f.predicted is not None)
    shown = np.array([f.gripper_m for f in frames[start:]])
    ahead = np.array([f.predicted.gripper_m for f in frames[start:]])

    def misfit(k: int) -> float:
        return float(np.median(np.linalg.norm(shown[k:] - ahead[: len(ahead) - k], axis=1)))

    return CONTROL_PERIOD_S * min(range(100), key=misfit)


@pytest.fixture(scope="module")
def runs(site_config: SiteConfig) -> dict[float, list[DisplayFrame]]:
    """One scripted hand (a synthetic operator's samples, recorded once) replayed under three
    one-way delays; what the operator was shown in each."""
    config = TrialConfig(modality="predictive", seed=3, timeout_s=9.0, site=site_config)
    with RemoteSite(config.site) as site:
        operator = trial_operator(site, config)
        recorder = _Scripted(operator)
        run_trial(recorder, config, site)
    script = [s for s in recorder.sent if s is not None]
    out = {}
    for delay_s in (0.0, 0.1, 0.2):
        delayed = TrialConfig(
            modality="predictive", timeout_s=9.0, network=NetworkConfig(delay_s=delay_s),
            site=site_config,
        )  # fmt: skip
        replay = _Scripted(operator, list(script))
        result = run_trial(replay, delayed)
        # Samples come late and bunch up under delay: the hand's record keeps each once.
        assert np.all(np.diff(result.hand_time_s) > 0)
        assert np.isfinite(result.to_row()["idle_share_xy"])
        out[delay_s] = replay.seen
    return out


def test_the_prediction_does_not_wait_for_the_network(runs: dict) -> None:
    """The model takes the samples as they are sent: the same predicted arm at every delay."""
    predicted = {
        d: np.array([f.predicted.arm_q_rad for f in frames if f.predicted is not None])
        for d, frames in runs.items()
    }
    n = min(len(p) for p in predicted.values())
    assert n > 500  # engaged for most of the 9 s
    for d in (0.1, 0.2):
        np.testing.assert_allclose(predicted[d][:n], predicted[0.0][:n], atol=1e-6)


def test_the_predictive_ghost_leads_the_delayed_ghost_by_the_round_trip(runs: dict) -> None:
    lead = {d: _lead_s(frames) for d, frames in runs.items()}
    # Without delay it leads by the arm's own tracking of its targets and a camera frame.
    assert 0.1 <= lead[0.0] <= 0.3, lead
    # The shown gripper moves only at the camera's frames: a lead is read to within one.
    for d in (0.1, 0.2):
        assert lead[d] - lead[0.0] == pytest.approx(2 * d, abs=CAMERA_PERIOD_S), lead


def test_before_the_arm_engages_the_two_ghosts_coincide(runs: dict) -> None:
    for frames in runs.values():
        waiting = [f for f in frames if f.predicted is None]
        assert len(waiting) > 100
        assert all(f.shown_predicted is None for f in waiting)  # the layer draws the frame's arm

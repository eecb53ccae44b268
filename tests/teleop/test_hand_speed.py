"""Hand speed: still hands read still through the wearable's noise; moving hands at their speed."""

import numpy as np
import pytest

from arteleop.errors import ConfigurationError
from arteleop.operator import ImuErrorConfig
from arteleop.teleop import HandSpeed, reconstruct
from tests.operator.motions import reach_and_return


def test_constant_velocity_reads_exactly() -> None:
    speed = HandSpeed(0.3)
    v = np.array([0.12, -0.05, 0.09])  # |v| = 0.158 m/s
    for k in range(100):
        t = k * 0.01
        speed.update(t, np.array([0.3, 0.1, 0.0]) + v * t)
    assert speed.speed_m_s == pytest.approx(float(np.linalg.norm(v)), rel=1e-9)


def test_a_hand_held_still_reads_still_through_jittery_imu_errors() -> None:
    """The reconstructed hand during the calibration hold of a recording whose orientation
    error is correlated over 0.2 s (jitter; the default's 3 s is gentler)."""
    rec = reach_and_return(errors=ImuErrorConfig(noise_correlation_s=0.2)).recording
    hand_path = reconstruct(rec)
    hold = hand_path.time_s < rec.time_s[0] + rec.info.calibration.hold_s
    t, hand = hand_path.time_s[hold], hand_path.hand_m[hold]
    naive = np.linalg.norm(np.diff(hand, axis=0), axis=1) / np.diff(t)
    speed = HandSpeed(0.3)
    readings = [speed.update(ti, pi) for ti, pi in zip(t, hand, strict=True)][30:]
    assert np.median(naive) > 0.1  # what sample-to-sample differences would report
    assert max(readings) < 0.05  # under the controller's engage threshold


def test_window_must_be_positive() -> None:
    with pytest.raises(ConfigurationError, match="window"):
        HandSpeed(0.0)

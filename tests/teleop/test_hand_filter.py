"""The robot side's 1€ filter on the reconstructed hand."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from arteleop.errors import ConfigurationError
from arteleop.operator import ImuErrorConfig, RecordingInfo, WearableConfig, record_hand_motion
from arteleop.teleop import HandFilter, HandFilterConfig, filter_hand_path, reconstruct
from tests.operator.motions import FAR, START

JITTERY = WearableConfig(errors=ImuErrorConfig(noise_correlation_s=0.2))


def _still_reach_still(seed: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A recorded hand (time, position, orientation), reconstructed as the controller does:
    1.5 s still, a 0.8 s minimum-jerk reach, 1.5 s still. The wearable's orientation error is
    correlated over 0.2 s: jitter, which the filter is for (the default's, over 3 s, drifts
    as slowly as a hand moves, and no filter of the hand may take it out)."""
    from arteleop.operator import minimum_jerk

    t = np.arange(0.0, 0.8, 0.01)
    hand = np.vstack([np.tile(START, (150, 1)), minimum_jerk(START, FAR, 0.8, t),
                      np.tile(FAR, (150, 1))])  # fmt: skip
    rotations = Rotation.from_euler("y", np.full((len(hand), 1), 0.4))
    rec = record_hand_motion(hand, rotations, np.zeros(len(hand)), RecordingInfo(rate_hz=100.0),
                             JITTERY, np.random.default_rng(seed))  # fmt: skip
    raw = reconstruct(rec.recording)
    return raw.time_s, raw.hand_m, raw.hand_quat_wxyz


@pytest.mark.parametrize("seed", [0, 1])
def test_the_filter_cuts_jitter_without_moving_the_resting_hand(seed: int) -> None:
    t, hand, quat = _still_reach_still(seed)
    filtered, filtered_quat = filter_hand_path(HandFilterConfig(), t, hand, quat)
    rest = t >= t[-1] - 1.0
    step = lambda p: np.median(np.linalg.norm(np.diff(p[rest], axis=0), axis=1))  # noqa: E731
    assert step(filtered) < step(hand) / 4  # measured: 1.7 mm a sample against 0.27
    assert np.linalg.norm(filtered[rest].mean(0) - hand[rest].mean(0)) < 0.001
    # It follows the reach: 10 cm into it, within the distance 50 ms of movement covers.
    reach = (t > 1.5 + 0.3) & (t < 1.5 + 0.5)
    speed = np.linalg.norm(np.diff(hand, axis=0), axis=1)[reach[1:]].max() / 0.01
    assert np.linalg.norm(filtered[reach] - hand[reach], axis=1).max() < 0.05 * speed
    np.testing.assert_allclose(np.linalg.norm(filtered_quat, axis=1), 1.0, atol=1e-12)


def test_a_disabled_filter_passes_the_hand_through() -> None:
    t, hand, quat = _still_reach_still(0)
    filtered, filtered_quat = filter_hand_path(HandFilterConfig(enabled=False), t, hand, quat)
    np.testing.assert_array_equal(filtered, hand)
    np.testing.assert_array_equal(filtered_quat, quat)


def test_an_orientation_sent_as_its_opposite_quaternion_is_the_same_rotation() -> None:
    """q and -q are one rotation: a stream that flips sign must not be averaged through 0."""
    f = HandFilter(HandFilterConfig(), 100.0)
    q = np.array([np.cos(0.2), 0.0, np.sin(0.2), 0.0])
    out = [f(i / 100, np.zeros(3), q if i % 2 else -q)[1] for i in range(50)]
    for got in out:
        assert abs(got @ q) == pytest.approx(1.0, abs=1e-12)


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"min_cutoff_hz": 0.0}, "HandFilterConfig.min_cutoff_hz = 0.0: expected a cutoff of "
         "0.01-100 Hz."),
        ({"derivative_cutoff_hz": float("nan")}, "HandFilterConfig.derivative_cutoff_hz = nan: "
         "expected a cutoff of 0.01-100 Hz."),
        ({"beta_per_m": -1.0}, "HandFilterConfig.beta_per_m = -1.0: expected 0-1000 (Hz per "
         "m/s; 0 is a plain low-pass filter)."),
    ],
)  # fmt: skip
def test_a_bad_filter_parameter_is_refused_by_name(kwargs: dict, message: str) -> None:
    with pytest.raises(ConfigurationError) as err:
        HandFilterConfig(**kwargs)
    assert str(err.value) == message

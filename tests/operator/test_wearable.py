import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from arteleop.errors import ConfigurationError
from arteleop.operator import (
    ArmAngles,
    ImuErrorConfig,
    WearableConfig,
    segment_rotations,
    simulate_wearable,
)
from arteleop.operator.wearable.simulator import WearableSimulator


def test_orientation_error_is_gauss_markov_with_the_stated_correlation() -> None:
    # The form, at a correlation time short enough for 400 s to pin its SD down.
    errors = ImuErrorConfig(
        noise_correlation_s=0.2, heading_drift_deg_per_sqrt_s=0.0, drop_probability=0.0
    )
    n = 40_000
    still = np.stack([segment_rotations(ArmAngles())] * n)
    sim = WearableSimulator(WearableConfig(errors=errors), np.random.default_rng(0))
    quats, _ = sim.run(still, n)
    ideal = WearableSimulator(
        WearableConfig(errors=ImuErrorConfig.ideal()), np.random.default_rng(0)
    )
    ref = Rotation.from_quat(ideal.sample(still[0])[0], scalar_first=True)
    x = (ref.inv() * Rotation.from_quat(quats[:, 0], scalar_first=True)).as_rotvec()
    np.testing.assert_allclose(x.std(axis=0), np.radians(1.0) / np.sqrt(3), rtol=0.1)
    lag1 = np.corrcoef(x[:-1, 0], x[1:, 0])[0, 1]
    assert lag1 == pytest.approx(np.exp(-1 / 20), abs=0.01)  # 0.2 s at 100 Hz


def _still(n: int = 20_000) -> np.ndarray:
    return np.stack([segment_rotations(ArmAngles(elbow_flexion=1.0))] * n)


def test_orientation_noise_is_1_deg_rms() -> None:
    errors = ImuErrorConfig(
        noise_correlation_s=0.2, heading_drift_deg_per_sqrt_s=0.0, drop_probability=0.0
    )
    cfg = WearableConfig(errors=errors)
    noisy = simulate_wearable(_still(), np.zeros(20_000), cfg, np.random.default_rng(1))
    clean = simulate_wearable(
        _still(1),
        np.zeros(1),
        WearableConfig(errors=ImuErrorConfig.ideal()),
        np.random.default_rng(1),
    )
    angles = (
        Rotation.from_quat(clean.sensor_quat_wxyz[0, 0], scalar_first=True).inv()
        * Rotation.from_quat(noisy.sensor_quat_wxyz[:, 0], scalar_first=True)
    ).magnitude()
    assert np.degrees(np.sqrt(np.mean(angles**2))) == pytest.approx(1.0, rel=0.05)


def test_heading_drift_is_a_random_walk_about_vertical() -> None:
    errors = ImuErrorConfig(
        noise_deg_rms=0.0, drop_probability=0.0, heading_drift_deg_per_sqrt_s=0.1
    )
    finals = []
    for seed in range(200):
        sig = simulate_wearable(
            _still(1000), np.zeros(1000), WearableConfig(errors=errors), np.random.default_rng(seed)
        )
        first = Rotation.from_quat(sig.sensor_quat_wxyz[0, 0], scalar_first=True)
        last = Rotation.from_quat(sig.sensor_quat_wxyz[-1, 0], scalar_first=True)
        d = last * first.inv()  # earth-frame rotation: about z only
        assert np.allclose(d.as_rotvec()[:2], 0.0, atol=1e-9)
        finals.append(d.as_rotvec()[2])
    # After ~10 s, std = 0.1 deg * sqrt(10 s).
    assert np.degrees(np.std(finals)) == pytest.approx(0.1 * np.sqrt(9.99), rel=0.15)


def test_drops_remove_whole_packets() -> None:
    errors = ImuErrorConfig(
        noise_deg_rms=0.0, heading_drift_deg_per_sqrt_s=0.0, drop_probability=0.02, drop_burst_max=3
    )
    sig = simulate_wearable(
        _still(10_000), np.zeros(10_000), WearableConfig(errors=errors), np.random.default_rng(2)
    )
    assert sig.dropped == 10_000 - len(sig.time_s)
    # A loss (mean length 2) can only start on a packet that arrives: lost fraction pE / (1 + pE).
    assert sig.dropped == pytest.approx(10_000 * 0.04 / 1.04, rel=0.3)
    steps = np.diff(sig.time_s)
    gaps = steps[steps > 0.015]
    # Losses last 1-3 packets; only losses that follow each other directly last longer.
    assert np.mean(gaps <= 0.04 + 1e-9) > 0.9


def test_bad_error_config() -> None:
    with pytest.raises(ConfigurationError, match=r"drop_probability=1.5 must be in"):
        ImuErrorConfig(drop_probability=1.5)


def test_sample_by_sample_equals_one_block() -> None:
    """The errors are drawn ahead in blocks, so the loop's per-sample calls give exactly the
    batch simulation's signals, across block boundaries and packet losses (to rounding: a
    block's quaternions come out of scipy, a sample's out of pinocchio)."""
    rng = np.random.default_rng(4)
    n = 1300
    angles = rng.uniform(-1.0, 1.0, (n, 7))
    segments = np.stack([segment_rotations(ArmAngles(*a)) for a in angles])
    config = WearableConfig(errors=ImuErrorConfig(drop_probability=0.05))
    batch, keep = WearableSimulator(config, np.random.default_rng(9)).run(segments, n)
    one_by_one = WearableSimulator(config, np.random.default_rng(9))
    samples = [one_by_one.sample(s) for s in segments]
    assert [q is not None for q in samples] == keep.tolist()
    assert 0 < one_by_one.dropped == n - keep.sum()
    kept = np.stack([q for q in samples if q is not None])
    np.testing.assert_allclose(kept, batch[keep], rtol=0, atol=1e-15)

"""Reconstructing a synthetic arm motion from its own IMU signals."""

from pathlib import Path

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from arteleop.errors import RecordingError
from arteleop.operator import ImuErrorConfig, load_recording, write_recording
from arteleop.operator.wearable.simulator import WearableConfig
from arteleop.teleop import SampleStatus, StreamingReconstructor, calibrate, reconstruct
from tests.operator.motions import reach_and_return


def _rms_error_m(syn, rec) -> float:
    traj = reconstruct(rec)
    idx = np.round(rec.time_s * rec.info.rate_hz).astype(int)
    return float(np.sqrt(np.mean(np.sum((traj.hand_m - syn.hand_m[idx]) ** 2, axis=1))))


@pytest.mark.parametrize("heading_rad", [0.0, 0.7])
def test_exact_without_sensor_errors(heading_rad: float) -> None:
    syn = reach_and_return(errors=ImuErrorConfig.ideal(), heading_rad=heading_rad)
    assert _rms_error_m(syn, syn.recording) < 1e-6  # far inside the 5 mm requirement


def test_calibration_recovers_the_mounting() -> None:
    syn = reach_and_return(errors=ImuErrorConfig.ideal())
    est = calibrate(syn.recording).segment_sensor_wxyz
    true = np.asarray(WearableConfig().mounting_wxyz)
    for e, t in zip(est, true, strict=True):
        angle = (
            Rotation.from_quat(e, scalar_first=True).inv()
            * Rotation.from_quat(t, scalar_first=True)
        ).magnitude()
        assert angle < 1e-9


def test_bounded_error_with_noise_drift_and_drops(tmp_path: Path) -> None:
    """Stated bound: 10 mm RMS with 1 deg noise, 0.1 deg/sqrt(s) heading drift, 1 % drops."""
    errors = []
    for seed in range(3):
        syn = reach_and_return(seed=seed, errors=ImuErrorConfig())
        write_recording(syn.recording, tmp_path / f"r{seed}.csv")
        rec = load_recording(tmp_path / f"r{seed}.csv")
        assert rec.report.filled_samples > 0  # drops were filled by slerp
        errors.append(_rms_error_m(syn, rec))
    assert max(errors) < 0.010
    assert min(errors) > 0.001  # the errors were really on


def test_calibration_refuses_a_moving_hold() -> None:
    syn = reach_and_return(errors=ImuErrorConfig.ideal())
    rec = syn.recording
    q = rec.sensor_quat_wxyz.copy()
    q[50, 1] = Rotation.from_euler("x", 30, degrees=True).as_quat(scalar_first=True)
    moved = type(rec)(rec.time_s, q, rec.grip, rec.info)
    with pytest.raises(
        RecordingError, match=r"forearm sensor turned .* hold the calibration posture"
    ):
        calibrate(moved)


def test_streaming_holds_short_gaps_and_reports_long_ones() -> None:
    syn = reach_and_return(errors=ImuErrorConfig.ideal())
    rec = syn.recording
    stream = StreamingReconstructor(rec.info.arm, calibrate(rec))
    batch = reconstruct(rec)
    assert stream.update(0.0, None, 0.0) is None  # nothing measured yet
    first = stream.update(rec.time_s[0], rec.sensor_quat_wxyz[0], rec.grip[0])
    assert first.status is SampleStatus.MEASURED
    np.testing.assert_allclose(first.hand_m, batch.hand_m[0], atol=1e-12)
    nan = np.full((3, 4), np.nan)
    statuses = [stream.update(rec.time_s[0] + 0.01 * k, nan, 0.0).status for k in range(1, 16)]
    assert statuses.count(SampleStatus.HELD) == 10  # up to 100 ms
    assert statuses[10:] == [SampleStatus.LOST] * 5
    assert (stream.held, stream.lost) == (10, 5)

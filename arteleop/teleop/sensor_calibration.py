"""Sensor-to-segment calibration from the posture held at the start of a recording."""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.spatial.transform import Rotation

from arteleop.errors import RecordingError
from arteleop.operator.wearable.arm_model import SEGMENTS, segment_rotations
from arteleop.operator.wearable.posture import CalibrationPosture
from arteleop.operator.wearable.recording import Recording
from arteleop.transforms import quats_to_matrices, rotations_z

MAX_POSTURE_SPREAD_DEG = 10.0
"""A sensor moving more than this during the hold means the posture was not held."""


@dataclass(frozen=True)
class SensorMounting:
    """Result of calibration: how each IMU sits on its segment, and where the torso faces.

    Attributes:
        segment_sensor_wxyz: (3, 4) ``q_segment_sensor`` for upper arm, forearm and hand.
        torso_heading_rad: Heading of the torso in the IMUs' earth frame.
    """

    segment_sensor_wxyz: NDArray[np.float64]
    torso_heading_rad: float

    def segment_orientations(self, sensor_quat_wxyz: ArrayLike) -> NDArray[np.float64]:
        """``R_torso_segment`` (N, 3, 3, 3) from (N, 3, 4) IMU quaternions.

        ``q_torso_segment = Rz(-heading) * q_earth_sensor * inverse(q_segment_sensor)``.
        """
        q = np.asarray(sensor_quat_wxyz, dtype=np.float64).reshape(-1, 3, 4)
        return self._torso_earth @ quats_to_matrices(q) @ self._sensor_segment

    @cached_property
    def _torso_earth(self) -> NDArray[np.float64]:
        return rotations_z(-self.torso_heading_rad)

    @cached_property
    def _sensor_segment(self) -> NDArray[np.float64]:
        """(3, 3, 3) inverse mountings, one per segment."""
        return quats_to_matrices(self.segment_sensor_wxyz).transpose(0, 2, 1)


def calibrate(recording: Recording, posture: CalibrationPosture | None = None) -> SensorMounting:
    """Estimate each sensor's mounting from the initial calibration hold of a recording."""
    posture = posture or recording.info.calibration
    hold = recording.time_s <= recording.time_s[0] + posture.hold_s
    return calibrate_from_hold(recording.sensor_quat_wxyz[hold], posture)


def calibrate_from_hold(
    sensor_quat_wxyz: NDArray[np.float64], posture: CalibrationPosture
) -> SensorMounting:
    """Mounting from (N, 3, 4) IMU samples taken while the operator held ``posture``.

    The mean orientation over the hold is compared with the known posture. Raises
    :class:`RecordingError` if there are too few samples or the operator moved during the hold.
    """
    quats = np.asarray(sensor_quat_wxyz, dtype=np.float64)
    if len(quats) < 10:
        raise RecordingError(
            f"Only {len(quats)} samples in the {posture.hold_s} s calibration hold; need 10."
        )
    torso_segment = segment_rotations(posture.angles)
    heading = Rotation.from_euler("z", posture.torso_heading_rad)
    mounting = np.empty((3, 4))
    for k, name in enumerate(SEGMENTS):
        samples = Rotation.from_quat(quats[:, k], scalar_first=True)
        mean = samples.mean()
        spread = float(np.degrees((mean.inv() * samples).magnitude().max()))
        if spread > MAX_POSTURE_SPREAD_DEG:
            raise RecordingError(
                f"The {name} sensor turned {spread:.0f} deg during the {posture.hold_s} s "
                f"calibration hold (at most {MAX_POSTURE_SPREAD_DEG:.0f} deg allowed): the "
                "operator must hold the calibration posture still at the start."
            )
        segment_sensor = (heading * Rotation.from_matrix(torso_segment[k])).inv() * mean
        mounting[k] = segment_sensor.as_quat(scalar_first=True, canonical=True)
    return SensorMounting(mounting, posture.torso_heading_rad)

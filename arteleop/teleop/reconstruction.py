"""From IMU orientations to the hand's pose in the operator's torso frame."""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum

import numpy as np
from numpy.typing import NDArray

from arteleop.errors import ConfigurationError
from arteleop.operator.wearable.arm_model import ArmModel, joint_positions
from arteleop.operator.wearable.recording import Recording
from arteleop.teleop.sensor_calibration import SensorMounting, calibrate
from arteleop.transforms import matrices_to_quats


@dataclass(frozen=True)
class HandTrajectory:
    """Reconstructed arm motion, torso frame (m).

    Attributes:
        time_s: (N,) sample times (s).
        joints_m: (N, 4, 3) shoulder, elbow, wrist and pinch point.
        hand_quat_wxyz: (N, 4) hand orientation.
        grip: (N,) pinch grip, 0..1.
    """

    time_s: NDArray[np.float64]
    joints_m: NDArray[np.float64]
    hand_quat_wxyz: NDArray[np.float64]
    grip: NDArray[np.float64]

    @property
    def hand_m(self) -> NDArray[np.float64]:
        """(N, 3) pinch point positions."""
        return self.joints_m[:, -1]

    def path_length_m(self) -> float:
        """Length of the pinch point's path (m)."""
        return float(np.linalg.norm(np.diff(self.hand_m, axis=0), axis=1).sum())


def reconstruct(
    recording: Recording, arm: ArmModel | None = None, mounting: SensorMounting | None = None
) -> HandTrajectory:
    """Reconstruct a whole recording; calibrates from its initial hold unless given ``mounting``."""
    arm = arm or recording.info.arm
    mounting = mounting or calibrate(recording)
    segments = mounting.segment_orientations(recording.sensor_quat_wxyz)
    hand = matrices_to_quats(segments[:, 2])
    return HandTrajectory(
        recording.time_s.copy(), joint_positions(arm, segments), hand, recording.grip.copy()
    )


class SampleStatus(Enum):
    """How a live sample was obtained."""

    MEASURED = "measured"
    HELD = "held"  # the sample was missing; the last measured pose is repeated
    LOST = "lost"  # missing for longer than the allowed gap: do not act on it


@dataclass(frozen=True)
class HandSample:
    """One reconstructed live sample (torso frame)."""

    time_s: float
    hand_m: NDArray[np.float64]
    hand_quat_wxyz: NDArray[np.float64]
    grip: float
    status: SampleStatus


class StreamingReconstructor:
    """Sample-by-sample reconstruction for live input, tolerant of dropped samples.

    A missing or non-finite sample repeats the last measured pose (``HELD``) for up to
    ``max_gap_s``; past that the status is ``LOST`` until a valid sample arrives.
    """

    def __init__(self, arm: ArmModel, mounting: SensorMounting, max_gap_s: float = 0.1) -> None:
        if max_gap_s <= 0:
            raise ConfigurationError(f"max_gap_s must be > 0, got {max_gap_s}")
        self.arm, self.mounting, self.max_gap_s = arm, mounting, max_gap_s
        self._last: HandSample | None = None
        self.held = 0
        self.lost = 0

    def update(
        self, time_s: float, sensor_quat_wxyz: NDArray[np.float64] | None, grip: float
    ) -> HandSample | None:
        """Reconstruct one sample; ``None`` only before the first valid sample."""
        q = None if sensor_quat_wxyz is None else np.asarray(sensor_quat_wxyz, dtype=np.float64)
        valid = q is not None and q.shape == (3, 4) and bool(np.isfinite(q).all())
        valid = valid and np.isfinite(grip)
        if valid:
            segments = self.mounting.segment_orientations(q)
            sample = HandSample(
                time_s,
                joint_positions(self.arm, segments)[0, -1],
                matrices_to_quats(segments[0, 2]),
                float(np.clip(grip, 0.0, 1.0)),
                SampleStatus.MEASURED,
            )
            self._last = sample
            return sample
        if self._last is None:
            return None
        status = (
            SampleStatus.HELD if time_s - self._last.time_s <= self.max_gap_s else SampleStatus.LOST
        )
        if status is SampleStatus.HELD:
            self.held += 1
        else:
            self.lost += 1
        last = self._last
        return HandSample(time_s, last.hand_m, last.hand_quat_wxyz, last.grip, status)

"""The posture the operator holds at the start of every trial, for the wearable's calibration,
and the hand's way from it to the working posture."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray
from scipy.spatial.transform import Rotation, Slerp

from arteleop.errors import ConfigurationError
from arteleop.operator.wearable.arm_model import ArmAngles, ArmModel, hand_pose, segment_rotations


@dataclass(frozen=True)
class CalibrationPosture:
    """The posture the operator holds at the start of every recording.

    Default: upper arm hanging, elbow at 90 deg, forearm pointing forward, thumb up.

    Attributes:
        angles: Joint angles of the posture.
        torso_heading_rad: Heading of the operator's torso in the IMUs' earth frame; the seat
            faces a known direction in the lab.
        hold_s: How long the posture is held at the start of the recording.
    """

    angles: ArmAngles = field(
        default_factory=lambda: ArmAngles(elbow_flexion=math.pi / 2, pronation=math.pi / 2)
    )
    torso_heading_rad: float = 0.0
    hold_s: float = 1.0

    def __post_init__(self) -> None:
        if self.hold_s <= 0:
            raise ConfigurationError(f"CalibrationPosture.hold_s must be > 0 s, got {self.hold_s}")


def hand_from_calibration(
    arm: ArmModel, calibration: CalibrationPosture, hand_pitch_rad: float
) -> tuple[NDArray[np.float64], Slerp]:
    """The hand's position in the calibration posture (torso frame, m), and the path of its
    rotation from that posture (0) to the working one, pitched ``hand_pitch_rad`` about the
    torso's y (1)."""
    position, R_hand = hand_pose(arm, segment_rotations(calibration.angles))
    path = [Rotation.from_matrix(R_hand), Rotation.from_euler("y", hand_pitch_rad)]
    return position, Slerp([0.0, 1.0], Rotation.concatenate(path))

"""Turn a hand motion into what the wearable would have recorded on a person making it.

The hand path goes through the arm model's inverse (elbow hanging naturally) to segment
orientations, then through the IMU model. Every recording starts with the calibration posture
held, then a minimum-jerk transition to the motion's first pose, as a person would do.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.spatial.transform import Rotation, Slerp

from arteleop.errors import ConfigurationError
from arteleop.operator.minimum_jerk import minimum_jerk_profile
from arteleop.operator.wearable.arm_model import (
    hand_pose,
    joint_positions,
    segment_rotations,
    segments_for_hand_pose,
)
from arteleop.operator.wearable.recording import Recording, RecordingInfo
from arteleop.operator.wearable.simulator import WearableConfig, simulate_wearable

TRANSITION_S = 1.0
"""Time to move from the calibration posture to the motion's first pose (s)."""


@dataclass(frozen=True)
class SynthesizedRecording:
    """A recording with the ground truth behind it.

    Attributes:
        recording: What the wearable delivered (dropped samples absent).
        time_s: (M,) every sample time, dropped or not.
        hand_m: (M, 3) true pinch point in the torso frame.
        hand_quat_wxyz: (M, 4) true hand orientation.
    """

    recording: Recording
    time_s: NDArray[np.float64]
    hand_m: NDArray[np.float64]
    hand_quat_wxyz: NDArray[np.float64]


def record_hand_motion(
    hand_m: ArrayLike,
    hand_rotations: Rotation,
    grip: ArrayLike,
    info: RecordingInfo,
    wearable: WearableConfig,
    rng: np.random.Generator,
) -> SynthesizedRecording:
    """Recording of a person moving the hand through ``hand_m`` (N, 3) at the wearable's rate."""
    hand_m = np.asarray(hand_m, dtype=np.float64)
    grip = np.asarray(grip, dtype=np.float64)
    if hand_m.ndim != 2 or hand_m.shape[1] != 3 or len(hand_rotations) != len(hand_m) != len(grip):
        raise ConfigurationError(
            f"hand motion shapes disagree: positions {hand_m.shape}, "
            f"{len(hand_rotations)} rotations, grip {grip.shape}"
        )
    if info.rate_hz != wearable.rate_hz:
        raise ConfigurationError(
            f"rate {info.rate_hz} Hz in info but {wearable.rate_hz} Hz in wearable"
        )
    rate = wearable.rate_hz
    calib = segment_rotations(info.calibration.angles)
    calib_pos, calib_rot = hand_pose(info.arm, calib)

    n_hold = round(info.calibration.hold_s * rate) + 1
    tau = minimum_jerk_profile(np.arange(1, round(TRANSITION_S * rate) + 1) / (TRANSITION_S * rate))
    blend_pos = calib_pos + np.outer(tau, hand_m[0] - calib_pos)
    calib_rot = Rotation.from_matrix(calib_rot)
    blend_rot = Slerp([0.0, 1.0], Rotation.concatenate([calib_rot, hand_rotations[0]]))(tau)

    positions = np.vstack([np.tile(calib_pos, (n_hold, 1)), blend_pos, hand_m])
    rotations = Rotation.concatenate([calib_rot] * n_hold + [blend_rot, hand_rotations])
    moving = zip(positions[n_hold:], rotations[n_hold:].as_matrix(), strict=True)
    segments = np.stack(
        [calib] * n_hold + [segments_for_hand_pose(info.arm, p, R) for p, R in moving]
    )
    grips = np.concatenate([np.full(n_hold + len(tau), grip[0]), grip])
    signals = simulate_wearable(segments, grips, wearable, rng)
    recording = Recording(signals.time_s, signals.sensor_quat_wxyz, signals.grip, info)
    return SynthesizedRecording(
        recording,
        np.arange(len(grips)) / rate,
        joint_positions(info.arm, segments)[:, -1],
        rotations.as_quat(scalar_first=True, canonical=True),
    )

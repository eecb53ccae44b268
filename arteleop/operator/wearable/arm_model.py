"""A human right arm: shoulder (3 DoF), elbow (flexion, pronation), wrist (2 DoF).

Frames (all right-handed, metres):
- torso: origin midway between the shoulder joint centres; x forward, y left, z up.
- segment frames (upper arm, forearm, hand): x along the bone from the proximal to the distal
  joint. In the anatomical posture (arm hanging, palm forward) every segment has y pointing left
  (the elbow's hinge axis) and z forward.

Joint angles (rad), right arm: shoulder flexion (arm forward), abduction (arm sideways, away from
the body), internal rotation; elbow flexion, forearm pronation; wrist flexion, radial deviation.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.spatial.transform import Rotation

from arteleop.errors import ConfigurationError

SEGMENTS: tuple[str, str, str] = ("upper_arm", "forearm", "hand")
_HANGING = Rotation.from_euler("y", np.pi / 2)  # segment x along -z_torso, z along +x_torso


@dataclass(frozen=True)
class ArmModel:
    """Segment lengths and shoulder position of the operator's right arm.

    Defaults are for an adult of 1.75 m from Winter's anthropometric ratios (Biomechanics and
    Motor Control of Human Movement, 4th ed., 2009, table 4.1): upper arm 0.186 H, forearm
    0.146 H; the hand segment ends at the pinch point between thumb and index, about 0.45 of
    the hand length (0.108 H); shoulder centres sit 0.105 H either side of the midline.

    Attributes:
        upper_arm_m: Shoulder to elbow joint centre.
        forearm_m: Elbow to wrist joint centre.
        hand_m: Wrist joint centre to the pinch point.
        shoulder_m: Right shoulder joint centre in the torso frame.
    """

    upper_arm_m: float = 0.3255
    forearm_m: float = 0.2555
    hand_m: float = 0.085
    shoulder_m: tuple[float, float, float] = (0.0, -0.184, 0.0)

    def __post_init__(self) -> None:
        for name in ("upper_arm_m", "forearm_m", "hand_m"):
            value = getattr(self, name)
            if not 0.02 <= value <= 1.0:
                raise ConfigurationError(f"ArmModel.{name}={value} m is outside [0.02, 1.0] m")

    @classmethod
    def from_height(cls, height_m: float) -> ArmModel:
        """Segment lengths scaled from body height with Winter's ratios."""
        if not 1.0 <= height_m <= 2.5:
            raise ConfigurationError(f"body height {height_m} m is outside [1.0, 2.5] m")
        h = height_m
        return cls(0.186 * h, 0.146 * h, 0.45 * 0.108 * h, (0.0, -0.105 * h, 0.0))

    @property
    def lengths_m(self) -> NDArray[np.float64]:
        return np.array([self.upper_arm_m, self.forearm_m, self.hand_m])


@dataclass(frozen=True)
class ArmAngles:
    """Joint angles of the right arm (rad); see the module docstring for their meaning."""

    shoulder_flexion: float = 0.0
    shoulder_abduction: float = 0.0
    shoulder_rotation: float = 0.0
    elbow_flexion: float = 0.0
    pronation: float = 0.0
    wrist_flexion: float = 0.0
    wrist_deviation: float = 0.0


def segment_rotations(angles: ArmAngles) -> NDArray[np.float64]:
    """``R_torso_segment`` of upper arm, forearm and hand, shape (3, 3, 3)."""
    a = angles
    shoulder = Rotation.from_euler("y", -a.shoulder_flexion) * Rotation.from_euler(
        "x", -a.shoulder_abduction
    )
    upper = shoulder * _HANGING * Rotation.from_euler("x", -a.shoulder_rotation)
    fore = (
        upper * Rotation.from_euler("y", -a.elbow_flexion) * Rotation.from_euler("x", a.pronation)
    )
    hand = (
        fore
        * Rotation.from_euler("y", -a.wrist_flexion)
        * Rotation.from_euler("z", a.wrist_deviation)
    )
    return Rotation.concatenate([upper, fore, hand]).as_matrix()


def joint_positions(arm: ArmModel, segments: ArrayLike) -> NDArray[np.float64]:
    """Shoulder, elbow, wrist and pinch point in the torso frame, shape (N, 4, 3).

    ``segments``: ``R_torso_segment`` of N postures, shape (N, 3, 3, 3) (or (3, 3, 3) for one).
    """
    rot = np.asarray(segments, dtype=np.float64).reshape(-1, 3, 3, 3)
    bones = rot[..., :, 0] * arm.lengths_m[None, :, None]  # each segment's x axis times length
    shoulder = np.broadcast_to(np.asarray(arm.shoulder_m), (len(rot), 1, 3))
    return np.concatenate([shoulder, shoulder + np.cumsum(bones, axis=1)], axis=1)


def hand_pose(
    arm: ArmModel, segments: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Pinch point (m) and ``R_torso_hand`` for one posture (segments (3, 3, 3)), torso frame."""
    return joint_positions(arm, segments)[0, -1], segments[2].copy()


def segments_for_hand_pose(
    arm: ArmModel, hand_position_m: ArrayLike, R_torso_hand: ArrayLike
) -> NDArray[np.float64]:
    """``R_torso_segment`` (3, 3, 3) that put the pinch point at ``hand_position_m`` (torso
    frame, m) with the hand's orientation ``R_torso_hand`` (3, 3).

    The arm's redundancy (the elbow's swivel about the shoulder-wrist line) is resolved the way a
    relaxed person does: the elbow hangs as low as it can. Targets beyond reach are pulled in to
    99.9 % of the arm's length along the shoulder-wrist line.
    """
    # Scalars and 3x3 matrices only, through math where numpy's per-call cost would dominate:
    # this runs at the wearable's rate in the loop.
    R_hand = np.asarray(R_torso_hand, dtype=np.float64)
    s = np.asarray(arm.shoulder_m)
    wrist = np.asarray(hand_position_m, dtype=np.float64) - R_hand[:, 0] * arm.hand_m
    lu, lf = arm.upper_arm_m, arm.forearm_m
    axis = wrist - s
    ax, ay, az = axis.tolist()
    d = math.sqrt(ax * ax + ay * ay + az * az)
    d_clamped = min(max(d, abs(lu - lf) * 1.001 + 1e-6), (lu + lf) * 0.999)
    n = axis / d
    wrist = s + n * d_clamped
    # Elbow on the circle around the shoulder-wrist axis; pick its lowest point.
    cos_a = (lu**2 + d_clamped**2 - lf**2) / (2 * lu * d_clamped)
    center = s + n * (lu * cos_a)
    radius = lu * math.sqrt(max(0.0, 1 - cos_a**2))
    down = np.array([0.0, 0.0, -1.0]) + n * n[2]
    if down @ down < 1e-18:  # arm pointing straight down or up: let the elbow go out
        down = np.array([0.0, -1.0, 0.0]) + n * n[1]
    elbow = center + down * (radius / math.sqrt(down @ down))
    x_u = (elbow - s) / lu
    x_f = (wrist - elbow) / lf
    cos_flexion = float(x_f @ x_u)
    z_u = x_f - cos_flexion * x_u  # the forearm bends towards the upper arm's z
    z_u /= math.sqrt(z_u @ z_u)
    y_u = np.array(
        (z_u[1] * x_u[2] - z_u[2] * x_u[1], z_u[2] * x_u[0] - z_u[0] * x_u[2],
         z_u[0] * x_u[1] - z_u[1] * x_u[0])
    )  # fmt: skip
    segments = np.empty((3, 3, 3))
    upper = segments[0]
    upper[:, 0], upper[:, 1], upper[:, 2] = x_u, y_u, z_u
    flexion = math.acos(min(1.0, max(-1.0, cos_flexion)))
    fore0 = upper @ _rot_y(-flexion)
    # Pronation takes the part of the wrist's rotation about the forearm's own axis: the first
    # angle of the intrinsic x-y-z decomposition of the wrist's rotation.
    rel = fore0.T @ R_hand
    segments[1] = fore0 @ _rot_x(math.atan2(-rel[1, 2], rel[2, 2]))
    segments[2] = R_hand
    return segments


def _rot_x(a: float) -> NDArray[np.float64]:
    c, s = math.cos(a), math.sin(a)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def _rot_y(a: float) -> NDArray[np.float64]:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])

"""From the operator's hand (torso frame) to a gripper target (Baxter's base frame).

The mapping is a fixed, documented similarity: ``p_gripper = offset + scale * p_hand`` with the
torso's axes aligned with the robot's (x forward, y left, z up), as if the operator stood where
Baxter stands. With scale 1 and offset (0.33, -0.10, 0.15) m, the hand works 35 cm in front of
the shoulders, between 8 cm left and 43 cm right of the midline and 15-30 cm below the shoulders,
to put the gripper over the start and target points from above: within 85 % of an adult's reach
(a test checks every grasp and carry position).

The gripper always points down; its yaw about the vertical follows the hand's yaw relative to the
yaw the hand had when the mapping was (re)centred, limited to ``max_yaw_rad``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pinocchio as pin
from numpy.typing import ArrayLike, NDArray

from arteleop.errors import ConfigurationError
from arteleop.transforms import quat_to_matrix

R_DOWN = np.diag([1.0, -1.0, -1.0])
"""Gripper pointing down: tool z along -z of the base, fingers opening along -y of the base."""


@dataclass(frozen=True)
class MappingConfig:
    """The hand-to-gripper mapping.

    Attributes:
        scale: Gripper displacement per hand displacement (1 = one to one).
        offset_m: Gripper position (base frame) when the hand is at the torso frame's origin.
        max_yaw_rad: Limit of the gripper's yaw about the vertical, either way.
        clutch_max_speed_m_s: The mapping may be re-centred only while the hand moves slower.
    """

    scale: float = 1.0
    offset_m: tuple[float, float, float] = (0.33, -0.10, 0.15)
    max_yaw_rad: float = 1.5
    clutch_max_speed_m_s: float = 0.02

    def __post_init__(self) -> None:
        if not 0.1 <= self.scale <= 10:
            raise ConfigurationError(f"MappingConfig.scale={self.scale} is outside [0.1, 10]")


def _yaw(quat_wxyz: ArrayLike) -> float:
    """Heading (rad) of the hand's x axis about the vertical."""
    x = quat_to_matrix(quat_wxyz)[:, 0]
    return float(np.arctan2(x[1], x[0]))


@dataclass
class HandToGripper:
    """The mapping's state: the current offset and the reference yaw of the hand."""

    config: MappingConfig = field(default_factory=MappingConfig)
    offset_m: NDArray[np.float64] = field(init=False)
    hand_yaw0_rad: float = 0.0

    def __post_init__(self) -> None:
        self.offset_m = np.asarray(self.config.offset_m, dtype=np.float64)

    def gripper_target(self, hand_m: ArrayLike, hand_quat_wxyz: ArrayLike) -> NDArray[np.float64]:
        """``T_base_gripper`` target (4x4) for a hand pose in the torso frame."""
        yaw = _yaw(hand_quat_wxyz) - self.hand_yaw0_rad
        yaw = float(
            np.clip(
                (yaw + np.pi) % (2 * np.pi) - np.pi,
                -self.config.max_yaw_rad,
                self.config.max_yaw_rad,
            )
        )
        T = np.eye(4)
        T[:3, :3] = pin.rpy.rpyToMatrix(0.0, 0.0, yaw) @ R_DOWN
        T[:3, 3] = self.offset_m + self.config.scale * np.asarray(hand_m, dtype=np.float64)
        return T

    def hand_position_for(self, gripper_m: ArrayLike) -> NDArray[np.float64]:
        """Hand position (torso frame) that puts the gripper at ``gripper_m``."""
        return (np.asarray(gripper_m, dtype=np.float64) - self.offset_m) / self.config.scale

    def recenter(
        self,
        hand_m: ArrayLike,
        hand_quat_wxyz: ArrayLike,
        gripper_m: ArrayLike,
        hand_speed_m_s: float,
    ) -> bool:
        """Clutch: make the current hand pose map onto the gripper's current position and yaw.

        Refused (returns False) unless the hand is nearly still.
        """
        if hand_speed_m_s > self.config.clutch_max_speed_m_s:
            return False
        self.offset_m = np.asarray(gripper_m, dtype=np.float64) - self.config.scale * np.asarray(
            hand_m, dtype=np.float64
        )
        self.hand_yaw0_rad = _yaw(hand_quat_wxyz)
        return True

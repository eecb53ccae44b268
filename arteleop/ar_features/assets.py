"""What the view draws besides the display frames: the robot model and the bowl's mesh."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType

import numpy as np
from numpy.typing import NDArray

from arteleop.arrays import frozen_array
from arteleop.errors import ConfigurationError


@dataclass(frozen=True)
class ViewAssets:
    """Plain data the layers need once, at start-up.

    Attributes:
        robot_urdf: The robot's URDF as the head camera renders it (the ghost is 1:1 with it).
        arm_joints: Names of the joints of ``DisplayFrame.arm_q_rad``, in its order.
        finger_joints: The gripper's finger joints: the first opens towards +q, the second
            towards -q.
        finger_stroke_m: Travel of each finger from closed to open (m).
        fixed_joints: Positions of every other joint of the URDF (rad or m).
        bowl_vertices_m: (V, 3) the bowl's mesh in its own frame (m).
        bowl_faces: (F, 3) its triangles.
    """

    robot_urdf: Path
    arm_joints: tuple[str, ...]
    finger_joints: tuple[str, str]
    finger_stroke_m: float
    fixed_joints: Mapping[str, float] = field(default_factory=dict)
    bowl_vertices_m: NDArray[np.float64] = field(default_factory=lambda: np.zeros((0, 3)))
    bowl_faces: NDArray[np.int32] = field(default_factory=lambda: np.zeros((0, 3), np.int32))

    def __post_init__(self) -> None:
        if not Path(self.robot_urdf).is_file():
            raise ConfigurationError(f"ViewAssets.robot_urdf: no URDF at {self.robot_urdf}")
        object.__setattr__(self, "fixed_joints", MappingProxyType(dict(self.fixed_joints)))
        object.__setattr__(self, "bowl_vertices_m", frozen_array(self.bowl_vertices_m))
        object.__setattr__(self, "bowl_faces", frozen_array(self.bowl_faces, np.int32))

    def joint_positions(self, arm_q_rad: NDArray[np.float64], closure: float) -> dict[str, float]:
        """Every joint's position for an arm configuration and a gripper closure (0..1)."""
        q = self.finger_stroke_m * (1.0 - closure)
        fingers = dict(zip(self.finger_joints, (q, -q), strict=True))
        arm = dict(zip(self.arm_joints, np.asarray(arm_q_rad).tolist(), strict=True))
        return {**self.fixed_joints, **arm, **fingers}

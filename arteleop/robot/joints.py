"""Baxter's joint names, limits and named poses."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from arteleop.errors import ArteleopError, ConfigurationError

RIGHT_ARM_JOINTS: tuple[str, ...] = (
    "right_s0",
    "right_s1",
    "right_e0",
    "right_e1",
    "right_w0",
    "right_w1",
    "right_w2",
)
LEFT_ARM_JOINTS: tuple[str, ...] = tuple(n.replace("right_", "left_") for n in RIGHT_ARM_JOINTS)
RIGHT_FINGER_JOINTS: tuple[str, str] = ("r_gripper_l_finger_joint", "r_gripper_r_finger_joint")
LEFT_FINGER_JOINTS: tuple[str, str] = ("l_gripper_l_finger_joint", "l_gripper_r_finger_joint")
HEAD_PAN_JOINT = "head_pan"

GRIPPER_FRAME = "right_gripper"
"""Tool frame between the finger tips: z points out of the gripper, fingers open along y."""


@dataclass(frozen=True)
class JointLimits:
    """Limits of a set of joints, in the order of ``names``, read from the URDF.

    Units: rad and rad/s for revolute joints, m and m/s for prismatic ones; effort in N m or N.
    """

    names: tuple[str, ...]
    lower: NDArray[np.float64]
    upper: NDArray[np.float64]
    velocity: NDArray[np.float64]
    effort: NDArray[np.float64]

    def __post_init__(self) -> None:
        for field in ("lower", "upper", "velocity", "effort"):
            arr = np.array(getattr(self, field), dtype=np.float64)
            if arr.shape != (len(self.names),):
                raise ConfigurationError(
                    f"JointLimits.{field} has shape {arr.shape}, expected ({len(self.names)},)"
                )
            arr.setflags(write=False)
            object.__setattr__(self, field, arr)
        # check() runs on every physics step: its bounds, with their tolerance, are made once.
        object.__setattr__(self, "_checked_lower", self.lower - 1e-9)
        object.__setattr__(self, "_checked_upper", self.upper + 1e-9)

    def check(
        self,
        q: NDArray[np.float64],
        what: str = "configuration",
        error: type[ArteleopError] = ConfigurationError,
    ) -> None:
        """Raise ``error`` naming the first joint outside its limits: a
        :class:`ConfigurationError` for a configured pose, an ``ArmCommandError`` at run time."""
        q = np.asarray(q, dtype=np.float64)
        if q.shape != (len(self.names),):
            raise error(f"{what} has shape {q.shape}, expected ({len(self.names)},)")
        # Runs on every physics step (each arm command): one vector test, names only on failure.
        outside = ~((self._checked_lower <= q) & (q <= self._checked_upper))  # NaN: outside
        if outside.any():
            i = int(np.argmax(outside))
            raise error(
                f"{what}: joint {self.names[i]} = {q[i]:.4f} is outside its limits "
                f"[{self.lower[i]:.4f}, {self.upper[i]:.4f}]"
            )


@dataclass(frozen=True)
class ArmPose:
    """Joint positions (rad) of both arms, in ``RIGHT_ARM_JOINTS`` / ``LEFT_ARM_JOINTS`` order."""

    right: tuple[float, ...]
    left: tuple[float, ...]
    gripper_closure: float = 0.0

    def as_dict(self) -> dict[str, float]:
        """Joint name -> position (rad) for both arms."""
        return dict(zip(RIGHT_ARM_JOINTS + LEFT_ARM_JOINTS, self.right + self.left, strict=True))


WORK_POSTURE: tuple[float, ...] = (0.09, 0.11, 1.48, 1.55, -1.68, 1.48, -2.27)
"""Right-arm posture (rad) the IK's posture task pulls towards while teleoperating: gripper down
over the table with the elbow out to the side, below the head camera's line of sight to the
table (found by solving the IK from 60 random seeds and keeping the most elbow-out solution)."""

REST_POSE = ArmPose(
    # Right arm raised and folded beside the torso, clear of the table and of the head camera's
    # view of it; gripper open. Chosen by rendering the head camera (see tests/robot).
    right=(-0.35, -1.2, 0.3, 2.3, -0.2, 0.6, 0.0),
    # Left arm folded out of the way; it takes no part in the task.
    left=(0.35, -1.2, -0.3, 2.3, 0.2, 0.6, 0.0),
    gripper_closure=0.0,
)

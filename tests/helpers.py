"""Test-only helpers that use PyBullet's own tools as an independent reference."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from arteleop.robot import GRIPPER_FRAME, RIGHT_ARM_JOINTS
from arteleop.scene import RemoteSite

# Gripper pointing straight down (tool z = -base z), fingers opening along base y.
DOWN_XYZW = (1.0, 0.0, 0.0, 0.0)


def reach_down(site: RemoteSite, tool_m: NDArray[np.float64], iterations: int = 8) -> float:
    """Teleport the right arm to a top-down gripper pose at ``tool_m`` with PyBullet's IK.

    Returns the remaining position error (m) of the gripper frame, measured in the simulator.
    """
    robot = site.robot
    link = robot.link_index[GRIPPER_FRAME]
    movable = list(robot.joint_index)
    for _ in range(iterations):
        q = site.client.calculateInverseKinematics(
            robot.body_id,
            link,
            list(tool_m),
            DOWN_XYZW,
            maxNumIterations=200,
            residualThreshold=1e-6,
        )
        solution = dict(zip(movable, q, strict=True))
        robot.set_joint_positions({n: solution[n] for n in RIGHT_ARM_JOINTS})
    robot.command_arm(robot.arm_positions())
    return float(np.linalg.norm(robot.link_transform(GRIPPER_FRAME)[:3, 3] - tool_m))


def ik_down(site: RemoteSite, tool_m: NDArray[np.float64]) -> NDArray[np.float64]:
    """Right-arm joint targets (rad) for a top-down gripper pose, seeded from the current state."""
    robot = site.robot
    q = site.client.calculateInverseKinematics(
        robot.body_id,
        robot.link_index[GRIPPER_FRAME],
        list(tool_m),
        DOWN_XYZW,
        maxNumIterations=200,
        residualThreshold=1e-6,
    )
    solution = dict(zip(robot.joint_index, q, strict=True))
    return np.array([solution[n] for n in RIGHT_ARM_JOINTS])

"""Baxter in PyBullet: fixed base at the world origin, position-controlled arms."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np
import pybullet as p
from numpy.typing import ArrayLike, NDArray
from pybullet_utils.bullet_client import BulletClient

from arteleop.errors import ConfigurationError
from arteleop.robot.description import BaxterDescription
from arteleop.robot.gripper import ElectricGripper, GripperConfig
from arteleop.robot.joints import (
    LEFT_ARM_JOINTS,
    LEFT_FINGER_JOINTS,
    RIGHT_ARM_JOINTS,
    RIGHT_FINGER_JOINTS,
    ArmPose,
    JointLimits,
)
from arteleop.transforms import pose_to_transform, quat_xyzw_to_wxyz


@dataclass(frozen=True)
class ArmControlConfig:
    """Position-control settings of the arm joints.

    Attributes:
        position_gain: PyBullet's ``positionGain`` (dimensionless, 0..1).
        velocity_gain: PyBullet's ``velocityGain`` (dimensionless, 0..1).
    """

    position_gain: float = 0.3
    velocity_gain: float = 1.0


class Baxter:
    """Baxter loaded into a PyBullet client, fixed at the world origin.

    The world frame is therefore Baxter's ``base`` frame: every pose this class returns is
    ``T_base_<link>``. Arm commands go through PyBullet position control with the URDF's effort
    and velocity limits; the right gripper is an :class:`ElectricGripper`.
    """

    def __init__(
        self,
        client: BulletClient,
        description: BaxterDescription,
        gripper_config: GripperConfig | None = None,
        control: ArmControlConfig | None = None,
    ) -> None:
        self._client = client
        self.control = control or ArmControlConfig()
        self.body_id = client.loadURDF(
            str(description.urdf_path),
            basePosition=(0.0, 0.0, 0.0),
            useFixedBase=True,
            flags=p.URDF_USE_INERTIA_FROM_FILE,
        )
        self.joint_index: dict[str, int] = {}
        self.link_index: dict[str, int] = {}
        limits: dict[str, tuple[float, float, float, float]] = {}
        for i in range(client.getNumJoints(self.body_id)):
            info = client.getJointInfo(self.body_id, i)
            name = info[1].decode()
            self.link_index[info[12].decode()] = i
            if info[2] in (p.JOINT_REVOLUTE, p.JOINT_PRISMATIC):
                self.joint_index[name] = i
                limits[name] = (info[8], info[9], info[11], info[10])
        self.right_arm_limits = _limits(RIGHT_ARM_JOINTS, limits)
        self.left_arm_limits = _limits(LEFT_ARM_JOINTS, limits)
        self.gripper = ElectricGripper(
            client,
            self.body_id,
            finger_joints=tuple(self.joint_index[n] for n in RIGHT_FINGER_JOINTS),
            finger_tip_links=(
                self.link_index["r_gripper_l_finger_tip"],
                self.link_index["r_gripper_r_finger_tip"],
            ),
            finger_limits=_limits(RIGHT_FINGER_JOINTS, limits),
            config=gripper_config,
        )
        self._left_fingers = tuple(self.joint_index[n] for n in LEFT_FINGER_JOINTS)

    @property
    def client(self) -> BulletClient:
        return self._client

    def reset(self, pose: ArmPose) -> None:
        """Teleport both arms and the gripper to ``pose`` and hold it with the motors."""
        self.right_arm_limits.check(np.asarray(pose.right), "ArmPose.right")
        self.left_arm_limits.check(np.asarray(pose.left), "ArmPose.left")
        for name, value in pose.as_dict().items():
            self._client.resetJointState(self.body_id, self.joint_index[name], value)
        for j in self._left_fingers:
            self._client.resetJointState(self.body_id, j, 0.0)
        self.gripper.reset(pose.gripper_closure)
        self.command_arm(pose.right)
        self._command(LEFT_ARM_JOINTS, pose.left, self.left_arm_limits)

    def command_arm(self, q_rad: ArrayLike) -> None:
        """Position targets (rad) of the right arm's joints, in ``RIGHT_ARM_JOINTS`` order."""
        q = np.asarray(q_rad, dtype=np.float64)
        self.right_arm_limits.check(q, "right arm target")
        self._command(RIGHT_ARM_JOINTS, q, self.right_arm_limits)

    def arm_positions(self) -> NDArray[np.float64]:
        """Measured right-arm joint positions (rad), in ``RIGHT_ARM_JOINTS`` order."""
        return self.joint_positions(RIGHT_ARM_JOINTS)

    def joint_positions(self, names: Sequence[str]) -> NDArray[np.float64]:
        """Measured positions of the named joints (rad or m)."""
        states = self._client.getJointStates(self.body_id, [self.joint_index[n] for n in names])
        return np.array([s[0] for s in states])

    def link_transform(self, link: str) -> NDArray[np.float64]:
        """``T_base_link`` (4x4) of a URDF link, from the current simulator state."""
        if link not in self.link_index:
            raise ConfigurationError(
                f"Unknown link '{link}'. Baxter's links: {sorted(self.link_index)}"
            )
        state = self._client.getLinkState(
            self.body_id, self.link_index[link], computeForwardKinematics=True
        )
        return pose_to_transform(state[4], quat_xyzw_to_wxyz(state[5]))

    def set_joint_positions(self, positions: Mapping[str, float]) -> None:
        """Teleport the named joints (no dynamics); used for kinematic checks."""
        for name, value in positions.items():
            self._client.resetJointState(self.body_id, self.joint_index[name], value)

    def _command(self, names: Sequence[str], q: ArrayLike, limits: JointLimits) -> None:
        self._client.setJointMotorControlArray(
            self.body_id,
            [self.joint_index[n] for n in names],
            p.POSITION_CONTROL,
            targetPositions=list(np.asarray(q, dtype=np.float64)),
            forces=list(limits.effort),
            positionGains=[self.control.position_gain] * len(names),
            velocityGains=[self.control.velocity_gain] * len(names),
        )


def _limits(
    names: Sequence[str], table: Mapping[str, tuple[float, float, float, float]]
) -> JointLimits:
    rows = np.array([table[n] for n in names])
    return JointLimits(
        names=tuple(names),
        lower=rows[:, 0],
        upper=rows[:, 1],
        velocity=rows[:, 2],
        effort=rows[:, 3],
    )

"""Baxter in PyBullet: fixed base at the world origin, position-controlled arms."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np
import pinocchio as pin
import pybullet as p
from numpy.typing import ArrayLike, NDArray
from pybullet_utils.bullet_client import BulletClient

from arteleop.errors import ArmCommandError, ConfigurationError
from arteleop.robot.description import BaxterDescription, freeze_joints
from arteleop.robot.gripper import ElectricGripper, GripperConfig
from arteleop.robot.joints import (
    GRIPPER_FRAME,
    HEAD_PAN_JOINT,
    LEFT_ARM_JOINTS,
    LEFT_FINGER_JOINTS,
    REST_POSE,
    RIGHT_ARM_JOINTS,
    RIGHT_FINGER_JOINTS,
    ArmPose,
    JointLimits,
)
from arteleop.robot.kinematics import BaxterKinematics
from arteleop.transforms import (
    invert_transform,
    pybullet_pose_to_transform,
    quat_wxyz_to_xyzw,
    transform_to_pose,
)


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

    By default only the right arm and its fingers move (``freeze_idle_joints``): the left arm
    (at ``left_arm_rad``), its fingers and the head are frozen into fixed joints and PyBullet
    merges the fixed links, which cuts a physics step about four-fold (benchmarks/bench_site.py).
    Every URDF link keeps its name for :meth:`link_transform`, which composes the merged link's
    pose with the fixed offset pinocchio reads from the same URDF. With
    ``freeze_idle_joints=False`` every joint stays movable and the left arm is held at
    ``left_arm_rad`` by its motors.
    """

    def __init__(
        self,
        client: BulletClient,
        description: BaxterDescription,
        gripper_config: GripperConfig | None = None,
        control: ArmControlConfig | None = None,
        left_arm_rad: Sequence[float] = REST_POSE.left,
        freeze_idle_joints: bool = True,
    ) -> None:
        self._client = client
        self.control = control or ArmControlConfig()
        self._motor_groups: dict[
            Sequence[str], tuple[list[int], list[float], list[float], list[float]]
        ] = {}
        self.left_arm_rad = tuple(float(v) for v in left_arm_rad)
        self.left_arm_limits = BaxterKinematics(description.urdf_path).limits(LEFT_ARM_JOINTS)
        self.left_arm_limits.check(np.asarray(self.left_arm_rad), "left arm pose")
        self.frozen = freeze_idle_joints
        flags = p.URDF_USE_INERTIA_FROM_FILE
        self.urdf_path = description.urdf_path
        """The URDF loaded: ``description``'s, with the idle joints fixed if frozen."""
        if freeze_idle_joints:
            idle = {
                **dict(zip(LEFT_ARM_JOINTS, self.left_arm_rad, strict=True)),
                **dict.fromkeys(LEFT_FINGER_JOINTS, 0.0),
                HEAD_PAN_JOINT: 0.0,
            }
            self.urdf_path = freeze_joints(description, idle)
            flags |= p.URDF_MERGE_FIXED_LINKS
        self.body_id = client.loadURDF(
            str(self.urdf_path), basePosition=(0.0, 0.0, 0.0), useFixedBase=True, flags=flags
        )
        self.joint_index: dict[str, int] = {}
        self.link_index: dict[str, int] = {}
        """PyBullet link index of each link that survived merging (the movable ones)."""
        link_of_joint: dict[str, int] = {}
        limits: dict[str, tuple[float, float, float, float]] = {}
        for i in range(client.getNumJoints(self.body_id)):
            info = client.getJointInfo(self.body_id, i)
            name = info[1].decode()
            self.link_index[info[12].decode()] = i
            link_of_joint[name] = i
            if info[2] in (p.JOINT_REVOLUTE, p.JOINT_PRISMATIC):
                self.joint_index[name] = i
                limits[name] = (info[8], info[9], info[11], info[10])
        self._frames = _frame_offsets(BaxterKinematics(self.urdf_path).model, link_of_joint)
        self.right_arm_limits = _limits(RIGHT_ARM_JOINTS, limits)
        self.gripper = ElectricGripper(
            client,
            self.body_id,
            finger_joints=tuple(self.joint_index[n] for n in RIGHT_FINGER_JOINTS),
            finger_links=(
                self._collision_link("r_gripper_l_finger_tip"),
                self._collision_link("r_gripper_r_finger_tip"),
            ),
            finger_limits=_limits(RIGHT_FINGER_JOINTS, limits),
            config=gripper_config,
        )

    @property
    def client(self) -> BulletClient:
        return self._client

    def reset(self, pose: ArmPose) -> None:
        """Teleport the arms and the gripper to ``pose`` and hold them with the motors."""
        if self.frozen and not np.allclose(pose.left, self.left_arm_rad, atol=1e-9):
            raise ConfigurationError(
                f"ArmPose.left={pose.left} differs from the left-arm pose this Baxter was built "
                f"with ({self.left_arm_rad}); the left arm is frozen. Build Baxter (or the site's "
                "rest_pose) with the left arm you want."
            )
        if not self.frozen:
            self.left_arm_limits.check(np.asarray(pose.left), "ArmPose.left")
            self.set_joint_positions(dict(zip(LEFT_ARM_JOINTS, pose.left, strict=True)))
            self.set_joint_positions(dict.fromkeys(LEFT_FINGER_JOINTS, 0.0))
            self._command(LEFT_ARM_JOINTS, pose.left, self.left_arm_limits)
        self.right_arm_limits.check(np.asarray(pose.right), "ArmPose.right")
        for name, value in zip(RIGHT_ARM_JOINTS, pose.right, strict=True):
            self._client.resetJointState(self.body_id, self.joint_index[name], value)
        self.gripper.reset(pose.gripper_closure)
        self.command_arm(pose.right)

    def command_arm(self, q_rad: ArrayLike) -> None:
        """Position targets (rad) of the right arm's joints, in ``RIGHT_ARM_JOINTS`` order."""
        q = np.asarray(q_rad, dtype=np.float64)
        self.right_arm_limits.check(q, "right arm target", ArmCommandError)
        self._command(RIGHT_ARM_JOINTS, q, self.right_arm_limits)

    def arm_positions(self) -> NDArray[np.float64]:
        """Measured right-arm joint positions (rad), in ``RIGHT_ARM_JOINTS`` order."""
        return self.joint_positions(RIGHT_ARM_JOINTS)

    def joint_positions(self, names: Sequence[str]) -> NDArray[np.float64]:
        """Measured positions of the named joints (rad or m)."""
        states = self._client.getJointStates(self.body_id, [self.joint_index[n] for n in names])
        return np.array([s[0] for s in states])

    def frame_link(self, frame: str) -> tuple[int, NDArray[np.float64]]:
        """(PyBullet link index, ``T_link_frame``) of a URDF link or joint frame; -1 is the base."""
        if frame not in self._frames:
            raise ConfigurationError(
                f"Unknown link '{frame}'. Baxter's links: {sorted(self._frames)}"
            )
        return self._frames[frame]

    def _collision_link(self, link: str) -> int:
        """The PyBullet link holding ``link``'s collision shapes: its own, or the one it was
        merged into."""
        return self.link_index.get(link, self.frame_link(link)[0])

    def link_transform(self, link: str) -> NDArray[np.float64]:
        """``T_base_link`` (4x4) of a URDF link, from the current simulator state."""
        index, T_link_frame = self.frame_link(link)
        if index < 0:
            return T_link_frame.copy()  # fixed to the base, which sits at the world origin
        state = self._client.getLinkState(self.body_id, index, computeForwardKinematics=True)
        return pybullet_pose_to_transform(state[4], state[5]) @ T_link_frame

    def pybullet_ik(
        self,
        T_base_target: ArrayLike,
        frame: str = GRIPPER_FRAME,
        max_iterations: int = 200,
    ) -> NDArray[np.float64]:
        """Right-arm joint positions (rad) from PyBullet's ``calculateInverseKinematics``, seeded
        from the current state; the baseline that mink is measured against, and a test tool.

        Args:
            T_base_target: Wanted ``T_base_frame`` (4x4).
            frame: Any URDF frame rigidly attached to the right arm.
            max_iterations: PyBullet's iteration cap.
        """
        index, T_link_frame = self.frame_link(frame)
        pos, quat = transform_to_pose(np.asarray(T_base_target) @ invert_transform(T_link_frame))
        q = self._client.calculateInverseKinematics(
            self.body_id,
            index,
            pos.tolist(),
            quat_wxyz_to_xyzw(quat).tolist(),
            maxNumIterations=max_iterations,
            residualThreshold=1e-6,
        )
        solution = dict(zip(self.joint_index, q, strict=True))
        return np.array([solution[n] for n in RIGHT_ARM_JOINTS])

    def set_joint_positions(self, positions: Mapping[str, float]) -> None:
        """Teleport the named joints (no dynamics); used for kinematic checks."""
        for name, value in positions.items():
            self._client.resetJointState(self.body_id, self.joint_index[name], value)

    def _command(self, names: Sequence[str], q: ArrayLike, limits: JointLimits) -> None:
        # Runs on every physics step: the lists that never change are built once per group.
        group = self._motor_groups.get(names)
        if group is None:
            n = len(names)
            group = self._motor_groups[names] = (
                [self.joint_index[name] for name in names],
                limits.effort.tolist(),
                [self.control.position_gain] * n,
                [self.control.velocity_gain] * n,
            )
        joints, forces, kp, kd = group
        self._client.setJointMotorControlArray(
            self.body_id,
            joints,
            p.POSITION_CONTROL,
            targetPositions=np.asarray(q, dtype=np.float64).tolist(),
            forces=forces,
            positionGains=kp,
            velocityGains=kd,
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


def _frame_offsets(
    model: pin.Model, link_of_joint: Mapping[str, int]
) -> dict[str, tuple[int, NDArray[np.float64]]]:
    """Each pinocchio frame -> (PyBullet link of its parent joint, ``T_link_frame``).

    Pinocchio's joint frame is the URDF frame of the joint's child link, which is also the frame
    PyBullet reports for that link, so a frame's placement in its parent joint is exactly its
    offset from the merged PyBullet link.
    """
    frames: dict[str, tuple[int, NDArray[np.float64]]] = {}
    for frame in model.frames:
        joint = frame.parentJoint
        link = -1 if joint == 0 else link_of_joint[model.names[joint]]
        frames.setdefault(frame.name, (link, frame.placement.homogeneous.copy()))
    return frames

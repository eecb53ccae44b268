"""Baxter: description (URDF), PyBullet body, gripper, kinematics (pinocchio) and reach."""

# First: it loads PyBullet without the banner PyBullet prints on import.
from arteleop.robot import native_output  # noqa: F401

# isort: split
from arteleop.robot.baxter import ArmControlConfig, Baxter
from arteleop.robot.command import ArmCommand
from arteleop.robot.description import (
    BaxterDescription,
    BaxterDescriptionConfig,
    find_baxter_urdf,
    load_baxter_description,
)
from arteleop.robot.gripper import ElectricGripper, GripperConfig
from arteleop.robot.joints import (
    GRIPPER_FRAME,
    HEAD_PAN_JOINT,
    LEFT_ARM_JOINTS,
    LEFT_FINGER_JOINTS,
    REST_POSE,
    RIGHT_ARM_JOINTS,
    RIGHT_FINGER_JOINTS,
    WORK_POSTURE,
    ArmPose,
    JointLimits,
)
from arteleop.robot.kinematics import BaxterKinematics
from arteleop.robot.reach import TopDownReach

__all__ = [
    "GRIPPER_FRAME",
    "HEAD_PAN_JOINT",
    "LEFT_ARM_JOINTS",
    "LEFT_FINGER_JOINTS",
    "REST_POSE",
    "RIGHT_ARM_JOINTS",
    "RIGHT_FINGER_JOINTS",
    "WORK_POSTURE",
    "ArmCommand",
    "ArmControlConfig",
    "ArmPose",
    "Baxter",
    "BaxterDescription",
    "BaxterDescriptionConfig",
    "BaxterKinematics",
    "ElectricGripper",
    "GripperConfig",
    "JointLimits",
    "TopDownReach",
    "find_baxter_urdf",
    "load_baxter_description",
]

"""PyBullet and pinocchio load the same URDF and must agree on every pose."""

from dataclasses import replace

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from arteleop.errors import ArmCommandError, ConfigurationError
from arteleop.robot import (
    GRIPPER_FRAME,
    LEFT_ARM_JOINTS,
    REST_POSE,
    RIGHT_ARM_JOINTS,
    RIGHT_FINGER_JOINTS,
    ArmCommand,
    BaxterKinematics,
)
from arteleop.scene import RemoteSite, SiteConfig

# The gripper, frames PyBullet merged into a moving link (finger tip, tool), frames merged into
# the base through the frozen head joint, and a frame on the frozen left arm.
FRAMES = (
    GRIPPER_FRAME,
    "right_wrist",
    "head",
    "head_camera_link",
    "r_gripper_l_finger_tip",
    "left_gripper",
    "base",
)


def test_pybullet_and_pinocchio_agree_on_100_random_configurations(site: RemoteSite) -> None:
    """pinocchio on the full URDF (every joint movable) against PyBullet's frozen, merged body."""
    kin = site.kinematics
    robot = site.robot
    rng = np.random.default_rng(42)
    names = list(robot.joint_index)
    assert sorted(names) == sorted(RIGHT_ARM_JOINTS + RIGHT_FINGER_JOINTS)
    frozen_left = dict(zip(LEFT_ARM_JOINTS, robot.left_arm_rad, strict=True))
    lower = kin.model.lowerPositionLimit
    upper = kin.model.upperPositionLimit
    worst_pos, worst_rot = 0.0, 0.0
    for _ in range(100):
        q = {n: rng.uniform(lower[kin._q_index[n]], upper[kin._q_index[n]]) for n in names}
        robot.set_joint_positions(q)
        T_pins = kin.frame_transforms(q | frozen_left, FRAMES)
        for frame, T_pin in zip(FRAMES, T_pins, strict=True):
            T_pb = robot.link_transform(frame)
            worst_pos = max(worst_pos, float(np.linalg.norm(T_pb[:3, 3] - T_pin[:3, 3])))
            dR = Rotation.from_matrix(T_pb[:3, :3].T @ T_pin[:3, :3])
            worst_rot = max(worst_rot, float(dR.magnitude()))
    assert worst_pos < 1e-6
    assert worst_rot < 1e-6


def test_arm_limits_are_the_urdf_limits(site: RemoteSite) -> None:
    pin_limits = site.kinematics.limits(RIGHT_ARM_JOINTS)
    pb_limits = site.robot.right_arm_limits
    for field in ("lower", "upper", "velocity", "effort"):
        np.testing.assert_allclose(getattr(pb_limits, field), getattr(pin_limits, field))
    # Values straight from the URDF text.
    assert pin_limits.lower[3] == pytest.approx(-0.05)
    assert pin_limits.upper[3] == pytest.approx(2.618)
    assert pin_limits.velocity[4] == pytest.approx(4.0)


def test_unknown_names_are_reported_with_the_valid_ones(site: RemoteSite) -> None:
    kin: BaxterKinematics = site.kinematics
    with pytest.raises(ConfigurationError, match=r"Unknown joint 'right_elbow'.*right_e1"):
        kin.configuration({"right_elbow": 0.0})
    with pytest.raises(ConfigurationError, match=r"Unknown frame 'gripper'.*right_gripper"):
        kin.frame_transform({}, "gripper")
    with pytest.raises(ConfigurationError, match=r"Unknown link 'hand'"):
        site.robot.link_transform("hand")


def test_arm_targets_outside_limits_are_refused(site: RemoteSite) -> None:
    q = site.observe().arm_q_rad.copy()
    q[3] = 3.0
    with pytest.raises(
        ArmCommandError,
        match=r"^right arm target: joint right_e1 = 3.0000 is outside its limits "
        r"\[-0.0500, 2.6180\]$",
    ):
        site.apply(ArmCommand(q_rad=q))
    q[3] = REST_POSE.right[3]
    q[5] = np.nan
    with pytest.raises(ArmCommandError, match=r"joint right_w1 = nan is outside"):
        site.robot.command_arm(q)
    with pytest.raises(ArmCommandError, match=r"ArmCommand.q_rad must be 7 finite joint"):
        ArmCommand(q_rad=q)


def test_frozen_left_arm_refuses_another_pose(site: RemoteSite) -> None:
    moved = replace(REST_POSE, left=(0.0, *REST_POSE.left[1:]))
    with pytest.raises(ConfigurationError, match="left arm is frozen"):
        site.robot.reset(moved)


def test_unfrozen_robot_keeps_every_joint_and_the_same_gripper(
    site: RemoteSite, site_config: SiteConfig
) -> None:
    with RemoteSite(replace(site_config, freeze_idle_joints=False)) as whole:
        assert set(LEFT_ARM_JOINTS) <= set(whole.robot.joint_index)
        assert len(whole.robot.link_index) > 2 * len(site.robot.link_index)
        whole.step(240)
        held = whole.robot.joint_positions(LEFT_ARM_JOINTS)
        np.testing.assert_allclose(held, REST_POSE.left, atol=0.02)  # motors hold it up
        np.testing.assert_allclose(whole.gripper_gap_range_m, site.gripper_gap_range_m, atol=1e-6)
        for frame in (GRIPPER_FRAME, "head_camera_link", "left_gripper"):
            np.testing.assert_allclose(
                whole.robot.link_transform(frame), site.robot.link_transform(frame), atol=0.02
            )

"""Trajectory, hand-to-gripper mapping and grip hysteresis."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from arteleop.errors import ConfigurationError
from arteleop.operator import ArmModel
from arteleop.robot.grip_control import GripCommand, GripHysteresis
from arteleop.robot.mapping import R_DOWN, HandToGripper
from arteleop.robot.trajectory import JointTrajectory, TrajectoryLimits
from arteleop.scene import GRASP_DEPTH_M, Workspace

LIMITS = TrajectoryLimits(velocity_rad_s=(1.5, 1.5, 1.5, 1.5, 4.0, 4.0, 4.0))


def test_trajectory_reaches_the_target_within_all_limits() -> None:
    dt = 1 / 240
    traj = JointTrajectory(LIMITS, dt, np.zeros(7))
    target = np.array([1.0, -0.5, 0.3, 1.2, -2.0, 0.7, 1.5])
    traj.set_target(target)
    q = [traj.position]
    for _ in range(1200):
        q.append(traj.step())
    q = np.array(q)
    np.testing.assert_allclose(q[-1], target, atol=1e-9)
    v = np.diff(q, axis=0) / dt
    a = np.diff(v, axis=0) / dt
    j = np.diff(a, axis=0) / dt
    assert np.all(np.abs(v).max(axis=0) <= np.array(LIMITS.velocity_rad_s) * 1.001)
    assert np.all(np.abs(a).max(axis=0) <= np.array(LIMITS.acceleration_rad_s2) * 1.01)
    assert np.all(np.abs(j).max(axis=0) <= np.array(LIMITS.jerk_rad_s3) * 1.01)


def test_a_moving_target_is_followed_without_stopping() -> None:
    dt = 1 / 240
    traj = JointTrajectory(LIMITS, dt, np.zeros(7))
    speeds = []
    for k in range(300):
        t = k * dt
        if k % 3 == 0:  # new targets at ~100 Hz, moving at 0.5 rad/s
            traj.set_target(np.full(7, 0.5 * (t + 0.01)), np.full(7, 0.5))
        traj.step()
        speeds.append(traj.velocity[0])
    assert min(speeds[150:]) > 0.4  # steady tracking, no stop-and-go at each tick


def test_bad_trajectory_limits() -> None:
    with pytest.raises(ConfigurationError, match="needs 7 positive values"):
        TrajectoryLimits(velocity_rad_s=(1.0,) * 6)


def test_comfortable_reach_covers_start_and_target() -> None:
    """The fixed mapping puts every grasp over start and target within 85 % of the arm's reach."""
    ws, arm, mapping = Workspace(), ArmModel(), HandToGripper()
    reach = arm.upper_arm_m + arm.forearm_m + arm.hand_m
    for point in (ws.start_m, ws.target_m):
        for lift in (ws.bowl.height_m - GRASP_DEPTH_M, 0.20):  # grasp height and carry height
            for side in (-1, 1):
                gripper = point + [0.0, side * ws.bowl.rim_radius_m, lift]
                hand = mapping.hand_position_for(gripper)
                assert np.linalg.norm(hand - arm.shoulder_m) < 0.85 * reach
                assert hand[0] > 0.15  # in front of the body


def test_mapping_round_trip_yaw_and_clutch() -> None:
    m = HandToGripper()
    hand = np.array([0.4, -0.2, -0.2])
    q_hand = Rotation.from_euler("z", 0.3).as_quat(scalar_first=True)
    T = m.gripper_target(hand, q_hand)
    np.testing.assert_allclose(m.hand_position_for(T[:3, 3]), hand, atol=1e-12)
    np.testing.assert_allclose(
        T[:3, :3], Rotation.from_euler("z", 0.3).as_matrix() @ R_DOWN, atol=1e-12
    )
    assert T[:3, 2] @ [0, 0, 1] == pytest.approx(-1.0)  # gripper points down
    assert not m.recenter(hand, q_hand, T[:3, 3] + 0.1, hand_speed_m_s=0.5)  # moving: refused
    assert m.recenter(hand, q_hand, T[:3, 3] + 0.1, hand_speed_m_s=0.0)
    T2 = m.gripper_target(hand, q_hand)
    np.testing.assert_allclose(T2[:3, 3], T[:3, 3] + 0.1, atol=1e-12)
    np.testing.assert_allclose(T2[:3, :3], R_DOWN, atol=1e-12)  # yaw re-zeroed at the clutch
    big = Rotation.from_euler("z", 3.0).as_quat(scalar_first=True)
    assert np.arctan2(*m.gripper_target(hand, big)[1::-1, 0]) == pytest.approx(1.5)  # yaw limited


def test_grip_hysteresis() -> None:
    g = GripCommand(GripHysteresis(close_at=0.6, open_at=0.4))
    assert [g.update(v) for v in (0.5, 0.61, 0.5, 0.41, 0.39, 0.5, 0.6)] == [0, 1, 1, 1, 0, 0, 1]
    with pytest.raises(ConfigurationError, match="open_at"):
        GripHysteresis(close_at=0.3, open_at=0.5)

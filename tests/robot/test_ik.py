"""mink IK on the MuJoCo model, checked against pinocchio's forward kinematics."""

import itertools

import mink
import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from arteleop.errors import ConfigurationError
from arteleop.robot import (
    GRIPPER_FRAME,
    REST_POSE,
    RIGHT_ARM_JOINTS,
    WORK_POSTURE,
    BaxterDescription,
    BaxterKinematics,
)
from arteleop.robot.ik import ArmIK, IKConfig
from arteleop.robot.ik_limits import HingeConfigurationLimit, KeptVelocityLimit
from arteleop.robot.mapping import R_DOWN
from arteleop.scene import Workspace


@pytest.fixture(scope="module")
def kin(description: BaxterDescription) -> BaxterKinematics:
    return BaxterKinematics(description.urdf_path)


@pytest.fixture
def ik(description: BaxterDescription, kin: BaxterKinematics) -> ArmIK:
    table = Workspace().table_box()
    limits = kin.limits(RIGHT_ARM_JOINTS)
    return ArmIK(
        description.urdf_path, limits, REST_POSE.right, table.center_m, table.half_extents_m
    )


def _fk(kin: BaxterKinematics, q: np.ndarray) -> np.ndarray:
    return kin.frame_transform(dict(zip(RIGHT_ARM_JOINTS, q, strict=True)), GRIPPER_FRAME)


def test_mujoco_and_pinocchio_agree_on_the_gripper(ik: ArmIK, kin: BaxterKinematics) -> None:
    rng = np.random.default_rng(0)
    lim = kin.limits(RIGHT_ARM_JOINTS)
    for _ in range(20):
        q = rng.uniform(lim.lower, lim.upper)
        ik.reset(q)
        np.testing.assert_allclose(ik.gripper_transform(), _fk(kin, q), atol=1e-9)


def test_solves_grasp_poses_over_start_and_target(ik: ArmIK, kin: BaxterKinematics) -> None:
    ws = Workspace()
    for point in (ws.start_m, ws.target_m):
        T = np.eye(4)
        T[:3, :3] = R_DOWN
        T[:3, 3] = point + [0.0, ws.bowl.rim_radius_m - 0.002, ws.bowl.height_m - 0.015]
        ik.reset(REST_POSE.right)
        ik.set_target(T)
        result = ik.solve()
        assert result.position_error_m < 1e-3 and result.orientation_error_rad < 1e-2
        # The answer is a real configuration: pinocchio puts the gripper on the target too.
        np.testing.assert_allclose(_fk(kin, result.q_rad)[:3, 3], T[:3, 3], atol=1e-3)
        kin.limits(RIGHT_ARM_JOINTS).check(result.q_rad)


def test_daqp_on_minks_rows_gives_minks_joints_to_the_bit(
    ik: ArmIK, description: BaxterDescription, kin: BaxterKinematics
) -> None:
    """The IK hands its rows to daqp itself, keeping the joint limits' fixed rows between
    steps; mink's own solve_ik (through qpsolvers) with mink's own limits must give the same
    joints, tick for tick, near the table (collision rows active) and out of reach (velocity
    limits active)."""
    table = Workspace().table_box()
    lim = kin.limits(RIGHT_ARM_JOINTS)
    reference = ArmIK(description.urdf_path, lim, REST_POSE.right,
                      table.center_m, table.half_extents_m)  # fmt: skip
    velocities = dict(zip(RIGHT_ARM_JOINTS, lim.velocity.tolist(), strict=True))
    joints = mink.ConfigurationLimit(reference.model)
    joints.lower = ik.limits[0].lower  # the elbow kept bent (IKConfig.elbow_min_bend_rad)
    minks_limits = [
        joints,
        mink.VelocityLimit(reference.model, velocities),
        *[x for x in reference.limits if isinstance(x, mink.CollisionAvoidanceLimit)],
    ]
    assert [type(x) for x in ik.limits] == [
        HingeConfigurationLimit,
        KeptVelocityLimit,
        mink.CollisionAvoidanceLimit,
    ]
    low = _fk(kin, np.array([0.3, -0.3, 0.0, 1.0, 0.0, 0.8, 0.0]))
    low[2, 3] = table.center_m[2] + table.half_extents_m[2] - 0.02  # under the table top
    far = low.copy()
    far[:3, 3] += [1.5, -0.5, 0.5]
    for arm in (ik, reference):
        arm.reset(REST_POSE.right)
    for target in (low, far):
        ik.set_target(target)
        reference.set_target(target)
        for _ in range(60):
            q = ik.step(0.01).q_rad
            v = mink.solve_ik(reference.configuration, reference.tasks, 0.01, "daqp", 1e-6,
                              limits=minks_limits)  # fmt: skip
            reference.configuration.integrate_inplace(v, 0.01)
            np.testing.assert_array_equal(q, reference.configuration.q)
    assert ik.step(0.01).position_error_m > 0.3, "premise: the far target is out of reach"


def test_kept_limit_rows_equal_minks_to_the_bit(ik: ArmIK, kin: BaxterKinematics) -> None:
    """Inside, on and beyond the joint limits, and for two step durations."""
    lim = kin.limits(RIGHT_ARM_JOINTS)
    velocities = dict(zip(RIGHT_ARM_JOINTS, lim.velocity.tolist(), strict=True))
    joints = mink.ConfigurationLimit(ik.model)
    joints.lower = ik.limits[0].lower
    pairs = [
        (ik.limits[0], joints),
        (ik.limits[1], mink.VelocityLimit(ik.model, velocities)),
    ]
    rng = np.random.default_rng(3)
    span = lim.upper - lim.lower
    for q in (*rng.uniform(lim.lower - 0.1 * span, lim.upper + 0.1 * span, (50, 7)),
              lim.lower, lim.upper):  # fmt: skip
        ik.reset(q)
        for dt in (0.01, 0.02, 0.01):
            for kept, minks in pairs:
                ours = kept.compute_qp_inequalities(ik.configuration, dt)
                theirs = minks.compute_qp_inequalities(ik.configuration, dt)
                np.testing.assert_array_equal(ours.G, theirs.G)
                np.testing.assert_array_equal(ours.h, theirs.h)


def test_hinge_limit_refuses_a_ball_joint() -> None:
    import mujoco

    model = mujoco.MjModel.from_xml_string(
        "<mujoco><worldbody><body><joint type='ball'/><geom size='0.1'/></body></worldbody>"
        "</mujoco>"
    )
    with pytest.raises(ConfigurationError, match="hinge or slide joints only"):
        HingeConfigurationLimit(model)


def test_each_step_respects_the_velocity_limits(ik: ArmIK, kin: BaxterKinematics) -> None:
    vmax = kin.limits(RIGHT_ARM_JOINTS).velocity
    T = _fk(kin, np.array([0.3, -0.3, 0.0, 1.0, 0.0, 0.8, 0.0]))
    ik.reset(REST_POSE.right)
    ik.set_target(T)
    q = np.array(REST_POSE.right)
    for _ in range(50):
        new = ik.step(0.01).q_rad
        assert np.all(np.abs(new - q) <= vmax * 0.01 + 1e-9)
        q = new


def test_out_of_reach_stops_at_the_nearest_pose_and_flags(ik: ArmIK) -> None:
    T = np.eye(4)
    T[:3, :3] = R_DOWN
    T[:3, 3] = (1.6, -0.3, 0.2)  # twice the arm's reach
    ik.reset(REST_POSE.right)
    ik.set_target(T)
    results = [ik.step(0.01) for _ in range(400)]
    assert not results[-1].reachable
    assert np.all(np.isfinite(results[-1].q_rad))
    # Converged to the nearest reachable pose: no motion at the end, nothing diverges.
    assert np.abs(results[-1].q_rad - results[-2].q_rad).max() < 1e-3
    # It rests within millimetres of the closest it came (the posture task pulls a little).
    closest = min(r.position_error_m for r in results)
    assert results[-1].position_error_m == pytest.approx(closest, abs=5e-3)


def test_collision_avoidance_keeps_the_gripper_above_the_table(ik: ArmIK) -> None:
    ws = Workspace()
    T = np.eye(4)
    T[:3, :3] = R_DOWN
    T[:3, 3] = ws.target_m + [0.0, 0.0, -0.05]  # 5 cm into the table
    ik.reset(REST_POSE.right)
    ik.set_target(T)
    for _ in range(400):
        result = ik.step(0.01)
    assert ik.gripper_transform()[2, 3] > ws.table_top_z_m
    assert result.position_error_m > 0.04


# Seed 3's P09, practice trial 1 (3879203): the IK's targets as the hand drove them (base frame,
# m), each reached in a straight line over the seconds given after it, from the joints it had.
TRAPPED_FROM_Q = (0.842, -0.682, -0.317, 1.679, 0.421, 0.641, 2.636)
TRAPPING_PATH = (
    ((0.65, -0.362, -0.116), 0.0), ((0.712, -0.751, 0.003), 1.2), ((0.712, -0.751, 0.003), 2.8),
    ((0.61, -0.421, 0.014), 1.0), ((0.462, -0.245, -0.026), 0.4), ((0.413, -0.152, -0.057), 0.4),
    ((0.27, -0.072, -0.026), 1.0), ((0.27, -0.072, -0.026), 1.0), ((0.582, -0.068, -0.007), 0.8),
    ((0.59, -0.06, -0.004), 1.0),
)  # fmt: skip


@pytest.mark.parametrize("elbow_min_bend_rad", [-0.05, IKConfig().elbow_min_bend_rad])
def test_an_arm_stretched_to_the_edge_of_its_reach_comes_back(
    description: BaxterDescription, kin: BaxterKinematics, elbow_min_bend_rad: float
) -> None:
    """Driven to the edge of its reach, the elbow straightens; at Baxter's own limit it stays
    straight, a singularity no step leaves, and the arm stays 17 cm from the reachable target
    that follows; kept bent (``elbow_min_bend_rad``), it comes back to it."""
    table = Workspace().table_box()
    config = IKConfig(elbow_min_bend_rad=elbow_min_bend_rad)
    ik = ArmIK(description.urdf_path, kin.limits(RIGHT_ARM_JOINTS), WORK_POSTURE,
               table.center_m, table.half_extents_m, config)  # fmt: skip
    ik.reset(TRAPPED_FROM_Q)
    T = np.eye(4)
    T[:3, :3] = Rotation.from_quat([0.0, 1.0, 0.01, 0.0], scalar_first=True).as_matrix()
    for (a, _), (b, duration_s) in itertools.pairwise(TRAPPING_PATH):
        n = round(duration_s / 0.01)
        for j in range(n):
            T[:3, 3] = np.add(a, np.subtract(b, a) * (j + 1) / n)
            ik.set_target(T)
            ik.step(0.01)
    for _ in range(500):
        result = ik.step(0.01)
    if elbow_min_bend_rad < 0:
        assert result.position_error_m > 0.15 and not result.reachable
    else:
        assert result.position_error_m < 0.005 and result.reachable


def test_an_elbow_bound_past_the_elbows_range_is_refused(
    description: BaxterDescription, kin: BaxterKinematics
) -> None:
    with pytest.raises(ConfigurationError, match=r"elbow_min_bend_rad=3.0: expected an angle"):
        ArmIK(description.urdf_path, kin.limits(RIGHT_ARM_JOINTS), WORK_POSTURE,
              config=IKConfig(elbow_min_bend_rad=3.0))  # fmt: skip

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from arteleop.transforms import (
    invert_transform,
    matrices_to_quats,
    pose_to_transform,
    pybullet_pose_to_transform,
    quat_to_matrix,
    quat_wxyz_to_xyzw,
    quat_xyzw_to_wxyz,
    quats_to_matrices,
    rotations_z,
    rotvecs_to_matrices,
    transform_points,
    transform_to_pose,
)


def test_quaternion_reordering_round_trip() -> None:
    q = np.array([0.1, 0.2, 0.3, 0.9])
    assert np.array_equal(quat_wxyz_to_xyzw(quat_xyzw_to_wxyz(q)), q)
    assert np.array_equal(quat_xyzw_to_wxyz([1.0, 2.0, 3.0, 4.0]), [4.0, 1.0, 2.0, 3.0])


@pytest.mark.parametrize("seed", range(5))
def test_pose_round_trip_and_inverse(seed: int) -> None:
    rng = np.random.default_rng(seed)
    q = Rotation.random(random_state=seed).as_quat(scalar_first=True, canonical=True)
    t = rng.normal(size=3)
    T = pose_to_transform(t, q)
    t2, q2 = transform_to_pose(T)
    np.testing.assert_allclose(t2, t, atol=1e-12)
    np.testing.assert_allclose(q2, q, atol=1e-12)
    np.testing.assert_allclose(invert_transform(T) @ T, np.eye(4), atol=1e-12)
    pts = rng.normal(size=(7, 3))
    np.testing.assert_allclose(
        transform_points(invert_transform(T), transform_points(T, pts)), pts, atol=1e-12
    )


def test_rotation_convention_is_active_w_first() -> None:
    # 90 deg about z maps x onto y.
    T = pose_to_transform([0, 0, 0], [np.cos(np.pi / 4), 0, 0, np.sin(np.pi / 4)])
    np.testing.assert_allclose(transform_points(T, [[1.0, 0, 0]]), [[0, 1.0, 0]], atol=1e-12)


def test_quat_to_matrix_normalises_and_matches_scipy() -> None:
    """pinocchio's conversion (fast, per sample) against scipy's (batch) on unnormalised input."""
    rng = np.random.default_rng(0)
    for q in Rotation.random(20, random_state=1).as_quat(scalar_first=True):
        scaled = q * rng.uniform(0.2, 5.0)
        np.testing.assert_allclose(
            quat_to_matrix(scaled),
            Rotation.from_quat(scaled, scalar_first=True).as_matrix(),
            atol=1e-12,
        )


def test_pybullet_poses_convert_as_the_general_path_does() -> None:
    rng = np.random.default_rng(5)
    for _ in range(200):
        q_xyzw = rng.normal(size=4)
        q_xyzw /= np.linalg.norm(q_xyzw)
        p = rng.normal(size=3)
        fast = pybullet_pose_to_transform(tuple(p), tuple(q_xyzw))
        np.testing.assert_allclose(
            fast, pose_to_transform(p, quat_xyzw_to_wxyz(q_xyzw)), atol=1e-12
        )


@pytest.mark.parametrize("n", [1, 3, 16, 17, 500])  # one by one in pinocchio up to 16, then scipy
def test_batch_conversions_match_scipy_on_either_path(n: int) -> None:
    rng = np.random.default_rng(n)
    rotations = Rotation.random(n, random_state=n)
    R = rotations.as_matrix().reshape(n, 1, 3, 3)
    q = rotations.as_quat(scalar_first=True, canonical=True).reshape(n, 1, 4)
    assert matrices_to_quats(R).shape == (n, 1, 4)
    np.testing.assert_allclose(matrices_to_quats(R), q, atol=1e-14)
    np.testing.assert_allclose(
        quats_to_matrices(q * rng.uniform(0.2, 5.0, (n, 1, 1))), R, atol=1e-14
    )
    # Down to angles where Rodrigues' closed form would cancel.
    rotvec = rng.normal(size=(n, 3)) * np.logspace(-9, 0.5, n)[:, None]
    np.testing.assert_allclose(
        rotvecs_to_matrices(rotvec), Rotation.from_rotvec(rotvec).as_matrix(), atol=1e-15
    )
    angle = rng.uniform(-4, 4, n)
    np.testing.assert_allclose(
        rotations_z(angle), Rotation.from_euler("z", angle[:, None]).as_matrix(), atol=1e-15
    )


def test_matrix_to_quaternion_keeps_w_non_negative_at_half_turns() -> None:
    """w is zero for half turns: the sign of the rest is then that of the matrix's axis."""
    for axis in np.eye(3):
        R = Rotation.from_rotvec(np.pi * axis).as_matrix()
        np.testing.assert_allclose(matrices_to_quats(R), np.concatenate([[0.0], axis]), atol=1e-15)
    q = matrices_to_quats(Rotation.from_rotvec([0.0, 0.0, -3.0]).as_matrix())
    assert q[0] > 0 and q[3] < 0

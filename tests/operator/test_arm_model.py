"""Analytic postures give known hand positions; the inverse reproduces any reachable pose."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from arteleop.errors import ConfigurationError
from arteleop.operator import (
    ArmAngles,
    ArmModel,
    hand_pose,
    joint_positions,
    segment_rotations,
    segments_for_hand_pose,
)

ARM = ArmModel()
S = np.asarray(ARM.shoulder_m)
LU, LF, LH = ARM.upper_arm_m, ARM.forearm_m, ARM.hand_m
HALF_PI = np.pi / 2


@pytest.mark.parametrize(
    ("angles", "expected"),
    [
        (ArmAngles(), [0.0, 0.0, -(LU + LF + LH)]),  # hanging
        (ArmAngles(elbow_flexion=HALF_PI), [LF + LH, 0.0, -LU]),  # forearm forward
        (ArmAngles(shoulder_flexion=HALF_PI), [LU + LF + LH, 0.0, 0.0]),  # arm forward
        (ArmAngles(shoulder_abduction=HALF_PI), [0.0, -(LU + LF + LH), 0.0]),  # arm sideways
        (ArmAngles(shoulder_flexion=np.pi), [0.0, 0.0, LU + LF + LH]),  # arm up
        # Upper arm down, elbow 90, upper arm rotated internally 90: forearm across the belly.
        (ArmAngles(elbow_flexion=HALF_PI, shoulder_rotation=HALF_PI), [0.0, LF + LH, -LU]),
        (ArmAngles(elbow_flexion=HALF_PI, wrist_flexion=HALF_PI), [LF, 0.0, -LU + LH]),
    ],
)
def test_analytic_postures(angles: ArmAngles, expected: list[float]) -> None:
    pos, _ = hand_pose(ARM, segment_rotations(angles))
    np.testing.assert_allclose(pos, S + expected, atol=1e-12)


def test_joint_positions_keep_segment_lengths() -> None:
    rng = np.random.default_rng(0)
    postures = [segment_rotations(ArmAngles(*rng.uniform(-1.5, 1.5, 7))) for _ in range(20)]
    joints = joint_positions(ARM, np.stack(postures))
    assert joints.shape == (20, 4, 3)
    np.testing.assert_allclose(
        np.linalg.norm(np.diff(joints, axis=1), axis=2), np.tile(ARM.lengths_m, (20, 1))
    )


def test_inverse_reproduces_reachable_poses() -> None:
    rng = np.random.default_rng(1)
    for _ in range(50):
        angles = ArmAngles(
            shoulder_flexion=rng.uniform(0.0, 1.5),
            shoulder_abduction=rng.uniform(-0.3, 0.8),
            shoulder_rotation=rng.uniform(-0.8, 0.8),
            elbow_flexion=rng.uniform(0.3, 2.2),
            pronation=rng.uniform(-1.0, 1.0),
            wrist_flexion=rng.uniform(-0.6, 0.6),
            wrist_deviation=rng.uniform(-0.3, 0.3),
        )
        p, r = hand_pose(ARM, segment_rotations(angles))
        segs = segments_for_hand_pose(ARM, p, r)
        p2, r2 = hand_pose(ARM, segs)
        np.testing.assert_allclose(p2, p, atol=1e-9)
        assert Rotation.from_matrix(r2.T @ r).magnitude() < 1e-9
        # The elbow is a hinge: the forearm stays in the upper arm's x-z plane.
        upper, fore = segs[0], segs[1]
        assert abs(np.dot(upper[:, 1], fore[:, 0])) < 1e-9


def test_from_height_and_validation() -> None:
    arm = ArmModel.from_height(1.75)
    assert arm.upper_arm_m == pytest.approx(0.3255)
    with pytest.raises(
        ConfigurationError, match=r"ArmModel.forearm_m=3.0 m is outside \[0.02, 1.0\] m"
    ):
        ArmModel(forearm_m=3.0)

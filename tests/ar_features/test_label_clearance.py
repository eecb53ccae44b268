"""The labels (the depth aids' height, the bars') keep clear of the target and the bowl on
screen."""

from __future__ import annotations

import numpy as np
import pytest

from arteleop.ar_features import (
    BAR_LABEL_GAP_M,
    DISTANCE_BAR_OFFSET_M,
    FOOT_RADIUS_M,
    GRIP_BAR_OFFSET_M,
    HEIGHT_LABEL_GAP_M,
    LABEL_CLEARANCE_M,
)
from arteleop.ar_features.clearance import discs_in_plane, pushed_out_m
from arteleop.transforms import make_transform
from tests.ar_features.frames import display_frame

# A camera 1 m above the gripper looking straight down: the image's x is the base's x, its
# y (down the image) the base's -y, and the table (z -0.2) 1.2 m away.
LOOKING_DOWN = make_transform(np.diag([1.0, -1.0, -1.0]), (0.5, -0.3, 1.0))
GRIPPER = make_transform(np.diag([1.0, -1.0, -1.0]), (0.5, -0.3, 0.0))
TABLE_Z = -0.2


def _frame(target_x_m: float, **overrides):
    fields = {
        "T_base_camera": LOOKING_DOWN,
        "T_base_gripper": GRIPPER,
        "bowl_m": None,
        "target_m": np.array([0.5 + target_x_m, -0.3, TABLE_Z]),
        "target_radius_m": 0.06,
    }
    return display_frame(**(fields | overrides))


def test_a_disc_is_seen_in_the_anchors_plane_by_its_depth() -> None:
    # 15 cm left on the table, 1.2 m away, seen in the gripper's plane 1 m away: x 1/1.2.
    ((centre, radius),) = discs_in_plane(LOOKING_DOWN, GRIPPER[:3, 3], [([0.35, -0.3, -0.2], 0.06)])
    np.testing.assert_allclose(centre, [-0.125, 0.0], atol=1e-12)
    assert radius == pytest.approx(0.05)
    # Nothing behind the camera is seen.
    assert discs_in_plane(LOOKING_DOWN, GRIPPER[:3, 3], [([0.5, -0.3, 2.0], 0.06)]) == []


def test_the_height_label_is_pushed_beyond_the_target_it_would_sit_on() -> None:
    # The ring over the target's middle (the gripper 10 cm above it): the label, 4.5 cm from
    # the ring, would lie on the 6 cm circle; it goes to the circle's edge and the clearance.
    over = make_transform(np.diag([1.0, -1.0, -1.0]), (0.5, -0.3, TABLE_Z + 0.1))
    frame = _frame(0.0, T_base_gripper=over, depth_aids=True)
    out = np.linalg.norm((frame.height_label_m() - frame.ring_m())[:2])
    # The ring is lifted FOOT_LIFT_M towards the camera, here straight up: 1.19 m from it, the
    # table 1.2 m.
    assert out == pytest.approx(0.06 * 1.19 / 1.2 + LABEL_CLEARANCE_M)
    # Well off the target it sits where it always did.
    aside = _frame(0.4, T_base_gripper=over, depth_aids=True)
    out = np.linalg.norm((aside.height_label_m() - aside.ring_m())[:2])
    assert out == pytest.approx(FOOT_RADIUS_M + HEIGHT_LABEL_GAP_M)


@pytest.mark.parametrize("offset", [DISTANCE_BAR_OFFSET_M, GRIP_BAR_OFFSET_M])
def test_a_bars_label_is_pushed_left_beyond_the_target_and_the_bowl(offset) -> None:
    # The gripper 20 cm above the table, 1 m from the camera; the target 20 cm left of it on
    # the table (1.2 m away), seen in the gripper's plane 1/1.2 as far and as large: its circle
    # spans 0.15-0.25 m left, where the label (0.17-0.27 m left) would lie on it.
    over = _frame(-0.24)
    label = over.bar_label_m(offset)
    left = GRIPPER[0, 3] - label[0]  # the label's right end, left of the gripper (m)
    assert left == pytest.approx((0.24 + 0.06) / 1.2 + LABEL_CLEARANCE_M)
    np.testing.assert_allclose(label[1:], over.beside_gripper_m(offset)[1:], atol=1e-12)
    # A tracked bowl there, its ring of grasp points at its grasp height, likewise.
    bowl = _frame(0.6, bowl_m=np.array([0.26, -0.3, TABLE_Z]))
    up = bowl.grasp_height_m
    (seen,) = discs_in_plane(LOOKING_DOWN, GRIPPER[:3, 3], [(bowl.bowl_m + [0, 0, up],
                                                            bowl.grasp_radius_m)])  # fmt: skip
    assert GRIPPER[0, 3] - bowl.bar_label_m(offset)[0] == pytest.approx(
        -seen[0][0] + seen[1] + LABEL_CLEARANCE_M
    )
    # Clear of both, it sits where it always did; the distance bar's is where perception reads.
    aside = _frame(0.4)
    assert GRIPPER[0, 3] - aside.bar_label_m(offset)[0] == pytest.approx(
        -offset[0] + BAR_LABEL_GAP_M
    )
    np.testing.assert_allclose(over.distance_label_m(), over.bar_label_m(DISTANCE_BAR_OFFSET_M))


def test_a_box_is_pushed_past_each_disc_level_with_it_in_turn() -> None:
    box = (0.045, 0.145, -0.015, 0.015)
    # Two discs one beyond the other: past the first, the box meets the second.
    discs = [(np.array([0.0, 0.0]), 0.06), (np.array([0.22, 0.0]), 0.05)]
    assert pushed_out_m(box, discs, 0.02) == pytest.approx(0.22 + 0.07 - 0.045)
    # A disc well above the box, or behind the anchor on the other side, is left as it is.
    assert pushed_out_m(box, [(np.array([0.1, -0.2]), 0.05)], 0.02) == 0.0
    assert pushed_out_m(box, [(np.array([-0.2, 0.0]), 0.05)], 0.02) == 0.0
    # On the left the same, mirrored.
    assert pushed_out_m((-0.145, -0.045, -0.015, 0.015), discs[:1], 0.02) == pytest.approx(0.035)

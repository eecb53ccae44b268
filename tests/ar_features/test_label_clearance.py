"""The bars' and the height's labels keep clear of the target and the bowl on screen."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from arteleop.ar_features import (
    DISTANCE_BAR_OFFSET_M,
    FOOT_RADIUS_M,
    HEIGHT_LABEL_GAP_M,
    LABEL_CLEARANCE_M,
    MODALITIES,
)
from arteleop.ar_features.clearance import clearance_m, discs_in_plane, pushed_out_m
from arteleop.ar_features.layers.bar import Bar
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
    # A box from 6 to 27 cm right, 3 cm tall: the disc 0.185 m from its near edge.
    assert clearance_m((0.06, 0.27, -0.015, 0.015), [(centre, radius)]) == pytest.approx(0.135)
    assert clearance_m((-0.27, -0.06, -0.015, 0.015), [(centre, radius)]) == pytest.approx(-0.05)
    assert clearance_m((0.0, 1.0, 0.0, 1.0), []) == float("inf")
    # Nothing behind the camera is seen.
    assert discs_in_plane(LOOKING_DOWN, GRIPPER[:3, 3], [([0.5, -0.3, 2.0], 0.06)]) == []


def test_the_bars_go_right_of_the_gripper_only_when_left_they_would_cover_the_target() -> None:
    covered = _frame(-0.15)
    assert covered.bars_rightward
    # Mirrored: the label's near end 1 cm beyond the bar's far end, 16 cm right, as far up.
    x, y = DISTANCE_BAR_OFFSET_M
    np.testing.assert_allclose(covered.distance_label_m(), [0.5 - x + 0.01, -0.3 - y, 0.0])
    np.testing.assert_allclose(covered.bar_start_m((x, y)), [0.5 + 0.06, -0.3 - y, 0.0])
    # The target right of the gripper, or under it: the bars stay left, as before.
    for target_x_m in (0.15, 0.0):
        frame = _frame(target_x_m)
        assert not frame.bars_rightward
        np.testing.assert_allclose(frame.distance_label_m(), [0.5 + x - 0.01, -0.3 - y, 0.0])
    # A tracked bowl on the right as well: left stays, the lesser harm of the two.
    bowl_right = np.array([0.5 + 0.15, -0.3, TABLE_Z])
    bowl = {"bowl_m": bowl_right, "grasp_height_m": 0.0, "grasp_radius_m": 0.06}
    assert not _frame(-0.15, **bowl).bars_rightward
    # The target mesh is kept clear of too: a target circle clear of the bars by 3 cm, beyond
    # LABEL_CLEARANCE_M, has its wider mesh reach within it.
    assert not _frame(-0.42).bars_rightward
    mesh = {"cues": MODALITIES["task"], "grasp_height_m": 0.0, "grasp_radius_m": 0.09}
    assert _frame(-0.42, **mesh).bars_rightward


def test_the_bar_draws_its_label_where_the_frame_says_reading_away_from_the_gripper() -> None:
    labels: dict[str, SimpleNamespace] = {}

    class Scene:
        def add_box(self, name: str, **kw) -> SimpleNamespace:
            return SimpleNamespace(**kw)

        def add_label(self, name: str, text: str, **kw) -> SimpleNamespace:
            labels[name] = SimpleNamespace(text=text, position=None, **kw)
            return labels[name]

    bar = Bar(Scene(), "/bar", (0, 255, 0), DISTANCE_BAR_OFFSET_M)  # type: ignore[arg-type]
    for frame, anchor in ((_frame(-0.15), "center-left"), (_frame(0.15), "center-right")):
        bar.show(frame, 0.5, "95 mm")
        np.testing.assert_allclose(labels["/bar/label"].position, frame.distance_label_m())
        assert labels["/bar/label"].anchor == anchor


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

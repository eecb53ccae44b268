"""The screen reader finds the target circle as the page draws it: broken by the cloud's gaps,
beside the depth aids' small ring and the line it hangs from, together as wide."""

import cv2
import numpy as np
import pytest

from tests.instruments.screen_reading import LINE_MARGIN_PX, Box, target_ring


def test_the_target_circle_is_read_whole_and_not_the_depth_aids_ring() -> None:
    rgb = np.full((400, 600, 3), 170, np.uint8)
    # The target circle, foreshortened, its drawn points leaving gaps a few pixels wide.
    cv2.ellipse(rgb, (150, 200), (45, 39), 0, 0, 360, (0, 0, 0), 4)
    for angle in (20, 140, 260):
        cv2.ellipse(rgb, (150, 200), (45, 39), 0, angle, angle + 1, (170, 170, 170), 4)
    # The depth aids: a small ring on the table, the drop line up to the gripper; 95 px wide.
    cv2.ellipse(rgb, (412, 330), (12, 8), 0, 0, 360, (10, 10, 10), 3)
    cv2.line(rgb, (412, 330), (495, 250), (10, 10, 10), 3)
    found = target_ring(rgb)
    assert found is not None
    assert abs(found.x_px - 150) <= 2 and abs(found.y_px - 200) <= 2, found
    assert 88 <= found.width_px <= 96, found


def test_the_scale_is_read_from_the_label_also_when_the_bars_change_sides() -> None:
    from tests.instruments.scripted_participant import LABEL_JUMP_MM, ScriptedParticipant

    # 0.6 px a millimetre; 10 cm of steps to the left; a label 60 px wide.
    start = Box(500.0, 300.0, 60.0, 20.0)
    along = Box(500.0 - 60.0, 300.0, 60.0, 20.0)
    assert ScriptedParticipant._scale(start, along, -1.0) == pytest.approx(0.6)
    # On the way the bars went right of the gripper: the label's near end (its right end, then
    # its left end, within the margin round its ink) moved 10 cm left and jumped LABEL_JUMP_MM
    # right.
    near = 500.0 + 30.0 - LINE_MARGIN_PX - 0.6 * 100.0 + 0.6 * LABEL_JUMP_MM
    jumped = Box(near + 29.0 - LINE_MARGIN_PX, 300.0, 58.0, 20.0)
    assert ScriptedParticipant._scale(start, jumped, -1.0) == pytest.approx(0.6)
    assert LABEL_JUMP_MM == pytest.approx(340.0)

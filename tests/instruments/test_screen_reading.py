"""The screen reader finds the target circle as the page draws it: broken by the cloud's gaps,
beside the depth aids' small ring and the line it hangs from, together as wide."""

import cv2
import numpy as np

from tests.instruments.screen_reading import target_ring


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

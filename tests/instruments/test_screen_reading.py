"""The screen reader finds the target circle as the page draws it: broken by the cloud's gaps,
beside a small dark ring and the line it hangs from, together as wide; a pointing study's cross
and circle, far off; and the depth aids' ring over a black mark, part of it hidden."""

import cv2
import numpy as np

from tests.instruments.screen_reading import circle_spot, cross_spot, foot_spot, target_ring


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


MAGENTA, GIZMO_RED = (255, 0, 255), (249, 45, 104)


def _aids_over_a_cross(ring_rgb: tuple[int, int, int]) -> np.ndarray:
    """A ring drawn as the aids' over the start cross, its drop line up to the gripper, the
    gripper's dark fingers over a third of it."""
    rgb = np.full((300, 400, 3), 170, np.uint8)
    cv2.line(rgb, (180, 130), (220, 170), (0, 0, 0), 6)
    cv2.line(rgb, (180, 170), (220, 130), (0, 0, 0), 6)
    cv2.ellipse(rgb, (203, 152), (11, 8), 0, 0, 360, ring_rgb, 3)
    cv2.line(rgb, (203, 152), (260, 60), ring_rgb, 3)
    cv2.rectangle(rgb, (190, 130), (203, 150), (40, 40, 40), -1)
    return rgb


def test_the_aids_ring_is_found_over_a_black_mark_under_the_fingers() -> None:
    found = foot_spot(_aids_over_a_cross(MAGENTA))
    assert found is not None
    # A circle fitted to the ellipse's seen two thirds: 3.5 px off, where the pointer takes the
    # ring within 8 px of a mark to be on it.
    assert np.hypot(found.x_px - 203, found.y_px - 152) <= 4, found
    assert foot_spot(_aids_over_a_cross(GIZMO_RED)) is None


def test_a_far_cross_with_an_arm_apart_is_the_cross_and_a_small_circle_the_circle() -> None:
    """As the markers 0.4 m off were seen: the cross's lowest arm a few pixels apart from the
    rest, whose box is then empty at its middle, and larger than the circle."""
    rgb = np.full((300, 400, 3), 170, np.uint8)
    middle = np.array([285.0, 125.0])
    for k, angle in enumerate(np.radians([20.0, 110.0, 200.0, 290.0])):
        way = np.array([np.cos(angle), np.sin(angle)])
        begin = middle + (12 if k == 1 else 0) * way  # the lowest arm, 110 degrees, apart
        end = middle + 32 * way
        cv2.line(rgb, tuple(begin.astype(int)), tuple(end.astype(int)), (0, 0, 0), 6)
    cv2.circle(rgb, (100, 200), 11, (0, 0, 0), 6)  # 29 px wide, its middle 16 px
    cross, circle = cross_spot(rgb), circle_spot(rgb)
    assert cross is not None and circle is not None
    assert np.hypot(circle.x_px - 100, circle.y_px - 200) <= 2, circle
    assert np.hypot(cross.x_px - middle[0], cross.y_px - middle[1]) <= 4, cross

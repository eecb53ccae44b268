"""The depth aids: a drop line from the gripper to the table, a ring at its foot and the
gripper's height, drawn where the frame says, whatever its AR cues."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from arteleop.ar_features import FOOT_LIFT_M, FOOT_RADIUS_M, MODALITIES
from arteleop.ar_features.layers import DepthAidsLayer
from arteleop.ar_features.layers.depth_aids import height_text
from arteleop.transforms import make_transform
from tests.ar_features.frames import GRIPPER_M, display_frame


class _Scene:
    """Keeps what a layer draws, by name, as viser's scene would hold it."""

    def __init__(self) -> None:
        self.nodes: dict[str, SimpleNamespace] = {}

    def add_line_segments(self, name: str, points, colors, **kw) -> SimpleNamespace:
        self.nodes[name] = SimpleNamespace(points=points, colors=colors, **kw)
        return self.nodes[name]

    def add_label(self, name: str, text: str, **kw) -> SimpleNamespace:
        self.nodes[name] = SimpleNamespace(text=text, position=None, **kw)
        return self.nodes[name]


def test_the_aids_hang_from_the_gripper_to_the_table_and_read_its_height() -> None:
    scene = _Scene()
    layer = DepthAidsLayer(scene)  # type: ignore[arg-type]
    line, ring, label = (scene.nodes[n] for n in ("/aids/drop_line", "/aids/foot", "/aids/height"))
    # Off unless the frame asks, under any cues; on under none.
    layer.draw(display_frame(cues=MODALITIES["full"]))
    assert not (line.visible or ring.visible or label.visible)
    frame = display_frame(cues=MODALITIES["none"], depth_aids=True)
    layer.draw(frame)
    assert line.visible and ring.visible and label.visible
    # The gripper at z -0.05 m, the table (where the target lies) at -0.2 m: 150 mm.
    top, foot = line.points[0].astype(float)
    np.testing.assert_allclose(top, GRIPPER_M, atol=1e-6)
    # The foot: where the line straight down meets the table, pulled FOOT_LIFT_M towards the
    # camera along its line of sight (in front of the table's cloud, and where the camera sees
    # the line meet the table).
    on_table = np.array([GRIPPER_M[0], GRIPPER_M[1], -0.2])
    camera = frame.viewpoint_m
    np.testing.assert_allclose(np.linalg.norm(foot - on_table), FOOT_LIFT_M, rtol=1e-4)
    sight = (camera - on_table) / np.linalg.norm(camera - on_table)
    np.testing.assert_allclose((foot - on_table) / FOOT_LIFT_M, sight, atol=1e-4)
    assert label.text == "height 150 mm"
    # The ring lies level about the foot.
    ends = ring.points.reshape(-1, 3).astype(float)
    np.testing.assert_allclose(ends[:, 2], foot[2], atol=1e-6)
    np.testing.assert_allclose(np.linalg.norm(ends[:, :2] - foot[:2], axis=1), FOOT_RADIUS_M,
                               rtol=1e-5)  # fmt: skip
    # The line passes a height between its ends on its way to the foot.
    halfway = frame.drop_line_at_m((GRIPPER_M[2] + foot[2]) / 2)
    np.testing.assert_allclose(halfway, (top + foot) / 2, atol=1e-6)
    np.testing.assert_allclose(frame.drop_line_at_m(GRIPPER_M[2]), top, atol=1e-6)
    # The label beside the ring, towards the image's middle (the camera's x is the base's x
    # here): this ring is right of it, so the label is left of it, read away from it.
    assert frame.height_label_leftward
    assert label.position[0] < foot[0] - FOOT_RADIUS_M and label.anchor == "center-right"
    on_the_left = display_frame(T_base_gripper=make_transform(np.eye(3), [0.1, 0.0, -0.05]))
    assert not on_the_left.height_label_leftward
    assert on_the_left.height_label_m()[0] > on_the_left.ring_m()[0] + FOOT_RADIUS_M
    layer.draw(display_frame(cues=MODALITIES["none"], depth_aids=False))
    assert not (line.visible or ring.visible or label.visible)


@pytest.mark.parametrize(
    ("height_m", "text"),
    [
        (0.1504, "height 150 mm"),
        (0.0006, "height 1 mm"),
        (0.0, "height 0 mm"),
        (-0.012, "height -12 mm"),
    ],
)
def test_the_height_is_read_to_the_millimetre(height_m: float, text: str) -> None:
    # The table (where the target lies) at -0.2 m.
    gripper = make_transform(np.eye(3), (0.68, -0.37, -0.2 + height_m))
    frame = display_frame(T_base_gripper=gripper, depth_aids=True)
    assert height_text(frame) == text
    assert frame.height_shown_m() == pytest.approx(int(text.split()[1]) / 1000)

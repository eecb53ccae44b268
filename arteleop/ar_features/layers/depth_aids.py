"""The depth aids: what a flat screen cannot show of the gripper's height, drawn in every
condition of a study that turns them on (not an AR cue): a line from the gripper straight down
to the table, a ring where it meets it, and the height in numbers."""

from __future__ import annotations

import numpy as np
import viser

from arteleop.ar_features.display_frame import FOOT_RADIUS_M, DisplayFrame
from arteleop.ar_features.layer import Layer
from arteleop.ar_features.layers.bar import LABEL_SCALE
from arteleop.ar_features.layers.colors import AIDS_RGB

DROP_LINE_WIDTH_PX = 3.0
FOOT_SEGMENTS = 24


def height_text(frame: DisplayFrame) -> str:
    """The label: the height above the table as the frame shows it
    (:meth:`DisplayFrame.height_shown_m`), in mm."""
    return f"height {1000 * frame.height_shown_m():.0f} mm"


class DepthAidsLayer(Layer):
    """Shown where the frame's ``depth_aids`` says, whatever its cues."""

    def __init__(self, scene: viser.SceneApi) -> None:
        super().__init__()
        empty = np.zeros((1, 2, 3), dtype=np.float32)
        self._line = scene.add_line_segments(
            "/aids/drop_line", empty, colors=AIDS_RGB, thickness=DROP_LINE_WIDTH_PX,
            thickness_units="screen", visible=False,
        )  # fmt: skip
        self._ring = scene.add_line_segments(
            "/aids/foot", np.zeros((FOOT_SEGMENTS, 2, 3), dtype=np.float32), colors=AIDS_RGB,
            thickness=DROP_LINE_WIDTH_PX, thickness_units="screen", visible=False,
        )  # fmt: skip
        self._label = scene.add_label(
            "/aids/height", "", font_screen_scale=LABEL_SCALE, anchor="center-left", visible=False
        )
        angles = np.linspace(0.0, 2 * np.pi, FOOT_SEGMENTS + 1)
        circle = FOOT_RADIUS_M * np.column_stack([np.cos(angles), np.sin(angles), 0 * angles])
        self._circle = np.stack([circle[:-1], circle[1:]], axis=1)

    def shown(self, frame: DisplayFrame) -> bool:
        return frame.depth_aids

    def update(self, frame: DisplayFrame) -> None:
        foot = frame.ring_m()
        self._line.points = np.stack([frame.gripper_m, foot])[None].astype(np.float32)
        self._ring.points = (self._circle + foot).astype(np.float32)
        self._label.position = frame.height_label_m()
        # Its end nearest the ring at the label's place: it reads away from the ring.
        self._label.anchor = "center-right" if frame.height_label_leftward else "center-left"
        self._label.text = height_text(frame)

    def _set_visible(self, visible: bool) -> None:
        for handle in (self._line, self._ring, self._label):
            handle.visible = visible

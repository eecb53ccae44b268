"""The depth aids: what a flat screen cannot show of the gripper's height, drawn in every
condition of a study that turns them on (not an AR cue): a line from the gripper straight down
to the table, a ring where it meets it, and the height in numbers."""

from __future__ import annotations

import numpy as np
import viser

from arteleop.ar_features.display_frame import HEIGHT_LABEL_STEP_M, DisplayFrame
from arteleop.ar_features.layer import Layer
from arteleop.ar_features.layers.colors import AIDS_RGB

DROP_LINE_WIDTH_PX = 3.0
FOOT_LIFT_M = 0.005
"""The ring and the line's foot are drawn this far above the table (m): the table's cloud points,
drawn facing the viewer, stand up to half a point's footprint proud of it and hid a ring on it."""
FOOT_RADIUS_M = 0.015
"""The ring on the table under the gripper (m): about 9 px at the head camera's 1.3 m."""
FOOT_SEGMENTS = 24
LABEL_GAP_M = 0.03
"""The height's label sits this far right of the ring, in the camera's image plane (m)."""


def height_text(height_m: float) -> str:
    """The label: the height above the table, to :data:`HEIGHT_LABEL_STEP_M`, in mm."""
    shown_mm = round(height_m / HEIGHT_LABEL_STEP_M) * HEIGHT_LABEL_STEP_M * 1000
    return f"height {shown_mm:.0f} mm"


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
            "/aids/height", "", font_screen_scale=0.9, anchor="center-left", visible=False
        )
        angles = np.linspace(0.0, 2 * np.pi, FOOT_SEGMENTS + 1)
        circle = FOOT_RADIUS_M * np.column_stack([np.cos(angles), np.sin(angles), 0 * angles])
        self._circle = np.stack([circle[:-1], circle[1:]], axis=1)

    def shown(self, frame: DisplayFrame) -> bool:
        return frame.depth_aids

    def update(self, frame: DisplayFrame) -> None:
        foot = frame.drop_foot_m() + [0.0, 0.0, FOOT_LIFT_M]
        self._line.points = np.stack([frame.gripper_m, foot])[None].astype(np.float32)
        self._ring.points = (self._circle + foot).astype(np.float32)
        right = frame.T_base_camera[:3, 0]
        self._label.position = foot + right * (FOOT_RADIUS_M + LABEL_GAP_M)
        self._label.text = height_text(frame.height_m())

    def _set_visible(self, visible: bool) -> None:
        for handle in (self._line, self._ring, self._label):
            handle.visible = visible

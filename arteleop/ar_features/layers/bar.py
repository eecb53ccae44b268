"""A bar in 3D near the gripper, facing the viewer: the filled part solid, the rest of its full
scale a translucent tint of the same colour, its value in numbers beside it. The distance and
grip bars are two of these. A bar without a value (the distance bar while the bowl is not
tracked) turns grey and empty, and its label says why."""

from __future__ import annotations

import numpy as np
import viser
from numpy.typing import NDArray

from arteleop.ar_features.display_frame import DisplayFrame
from arteleop.ar_features.layers.colors import NO_ESTIMATE_RGB
from arteleop.transforms import transform_to_pose

BAR_LENGTH_M = 0.10
"""Length of a full bar (m): about 60 px at the head camera's 1.3 m from the table."""
BAR_WIDTH_M = 0.012


SCALE_OPACITY = 0.3
LABEL_SCALE = 1.3
"""The labels' size, a multiple of the page's font (about 16 px tall at 1.3): read at a glance on
a laptop's screen, and by OCR (at 0.9 Tesseract misread one label in three)."""


class Bar:
    """One bar; ``offset_m`` places its left end in the camera's frame (x right, y down)
    relative to the gripper, so it sits beside the gripper on screen whatever the arm does. The
    label sits left of the bar, away from the gripper, and beyond the target and the bowl
    (:meth:`DisplayFrame.bar_label_m`)."""

    def __init__(
        self,
        scene: viser.SceneApi,
        name: str,
        rgb: tuple[int, int, int],
        offset_m: tuple[float, float],
    ) -> None:
        self._offset = offset_m
        self._rgb = rgb
        self._greyed = False
        dims = (BAR_LENGTH_M, BAR_WIDTH_M, BAR_WIDTH_M)
        self._frame = scene.add_box(
            f"{name}/scale", color=rgb, dimensions=dims, opacity=SCALE_OPACITY
        )
        self._fill = scene.add_box(f"{name}/fill", color=rgb, dimensions=dims)
        self._label = scene.add_label(
            f"{name}/label", "", font_screen_scale=LABEL_SCALE, anchor="center-right"
        )
        self.handles = (self._frame, self._fill, self._label)

    def show(self, frame: DisplayFrame, fraction: float | None, text: str) -> None:
        """Fill ``fraction`` (0..1) of the bar and write ``text`` beside it; None: no value,
        the bar greyed and empty."""
        R = frame.T_base_camera[:3, :3]
        start = frame.beside_gripper_m(self._offset)
        wxyz = transform_to_pose(frame.T_base_camera)[1]
        if (fraction is None) != self._greyed:
            self._greyed = fraction is None
            self._frame.color = NO_ESTIMATE_RGB if self._greyed else self._rgb
            self._fill.color = NO_ESTIMATE_RGB if self._greyed else self._rgb
        fraction = 0.0 if fraction is None else float(np.clip(fraction, 0.0, 1.0))
        length = max(fraction * BAR_LENGTH_M, 1e-4)
        self._place(self._frame, start + R[:, 0] * BAR_LENGTH_M / 2, wxyz)
        self._place(self._fill, start + R[:, 0] * length / 2, wxyz)
        self._fill.dimensions = (length, BAR_WIDTH_M * 1.2, BAR_WIDTH_M * 1.2)
        self._label.position = frame.bar_label_m(self._offset)
        self._label.text = text

    @staticmethod
    def _place(handle: viser.BoxHandle, center: NDArray[np.float64], wxyz: NDArray) -> None:
        handle.position = center
        handle.wxyz = wxyz

"""Manipulation cue: the blue bar of the gripper's closure."""

from __future__ import annotations

import viser

from arteleop.ar_features.display_frame import GRIP_BAR_OFFSET_M, DisplayFrame
from arteleop.ar_features.layer import Layer
from arteleop.ar_features.layers.bar import Bar
from arteleop.ar_features.layers.colors import GRIP_RGB


class GripBarLayer(Layer):
    """The bar fills as the gripper closes; its label gives the closure in percent."""

    cue = "grip_bar"

    def __init__(self, scene: viser.SceneApi) -> None:
        super().__init__()
        self._bar = Bar(scene, "/ar/grip_bar", GRIP_RGB, GRIP_BAR_OFFSET_M)

    def update(self, frame: DisplayFrame) -> None:
        c = frame.gripper_closure
        self._bar.show(frame, c, f"grip {c * 100:.0f} %")

    def _set_visible(self, visible: bool) -> None:
        for handle in self._bar.handles:
            handle.visible = visible

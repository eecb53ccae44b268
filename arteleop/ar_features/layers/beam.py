"""Manipulation cue: the red beam, the shortest path from the gripper to the closest grasp point."""

from __future__ import annotations

import numpy as np
import viser

from arteleop.ar_features.display_frame import DisplayFrame
from arteleop.ar_features.layer import Layer
from arteleop.ar_features.layers.colors import BEAM_RGB

BEAM_WIDTH_PX = 4.0


class BeamLayer(Layer):
    """A straight red segment from the gripper's tool frame to :meth:`DisplayFrame.grasp_point_m`,
    redrawn every frame; hidden while the camera does not track the bowl (no grasp point)."""

    cue = "beam"

    def __init__(self, scene: viser.SceneApi) -> None:
        super().__init__()
        self._handle = scene.add_line_segments(
            "/ar/beam",
            np.zeros((1, 2, 3), dtype=np.float32),
            colors=BEAM_RGB,
            thickness=BEAM_WIDTH_PX,
            thickness_units="screen",
            visible=False,
        )

    def update(self, frame: DisplayFrame) -> None:
        grasp = frame.grasp_point_m()
        if self._handle.visible != (grasp is not None):
            self._handle.visible = grasp is not None
        if grasp is not None:
            self._handle.points = np.stack([frame.gripper_m, grasp])[None].astype(np.float32)

    def _set_visible(self, visible: bool) -> None:
        self._handle.visible = visible

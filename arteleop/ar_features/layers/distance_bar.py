"""Manipulation cue: the green bar of the distance from the gripper to the closest grasp point."""

from __future__ import annotations

import viser

from arteleop.ar_features.display_frame import (
    DISTANCE_BAR_OFFSET_M,
    DISTANCE_LABEL_STEP_M,
    DisplayFrame,
)
from arteleop.ar_features.layer import Layer
from arteleop.ar_features.layers.bar import Bar
from arteleop.ar_features.layers.colors import DISTANCE_RGB

FULL_SCALE_M = 0.30
"""A distance that fills the bar (m): the reach from above the bowl, most of a trial."""
NOT_TRACKED_LABEL = "bowl not tracked"


class DistanceBarLayer(Layer):
    """The bar fills with the gripper-to-grasp-point distance; its label gives it in mm. While
    the camera does not track the bowl it is grey and empty, labelled "bowl not tracked"."""

    cue = "distance_bar"

    def __init__(self, scene: viser.SceneApi) -> None:
        super().__init__()
        self._bar = Bar(scene, "/ar/distance_bar", DISTANCE_RGB, DISTANCE_BAR_OFFSET_M)

    def update(self, frame: DisplayFrame) -> None:
        d = frame.grasp_distance_m()
        if d is None:
            self._bar.show(frame, None, NOT_TRACKED_LABEL)
        else:
            shown_mm = round(d / DISTANCE_LABEL_STEP_M) * DISTANCE_LABEL_STEP_M * 1000
            self._bar.show(frame, d / FULL_SCALE_M, f"{shown_mm:.0f} mm")

    def _set_visible(self, visible: bool) -> None:
        for handle in self._bar.handles:
            handle.visible = visible

"""Task cue: a green 1:1 mesh of the bowl at its target; placed when the real bowl coincides."""

from __future__ import annotations

import viser

from arteleop.ar_features.assets import ViewAssets
from arteleop.ar_features.display_frame import DisplayFrame
from arteleop.ar_features.layer import Layer
from arteleop.ar_features.layers.colors import TARGET_RGB

TARGET_OPACITY = 0.55
"""Translucent, so the real bowl's points show through when the two coincide."""


class TargetLayer(Layer):
    """The bowl's mesh, upright, its frame at the target point."""

    cue = "target_mesh"

    def __init__(self, scene: viser.SceneApi, assets: ViewAssets) -> None:
        super().__init__()
        self._handle = scene.add_mesh_simple(
            "/ar/target",
            assets.bowl_vertices_m,
            assets.bowl_faces,
            color=TARGET_RGB,
            opacity=TARGET_OPACITY,
            visible=False,
        )

    def update(self, frame: DisplayFrame) -> None:
        self._handle.position = frame.target_m

    def _set_visible(self, visible: bool) -> None:
        self._handle.visible = visible

"""The head camera's point cloud: the remote scene itself, drawn under every modality."""

from __future__ import annotations

import viser

from arteleop.ar_features.display_frame import DisplayFrame
from arteleop.ar_features.layer import Layer

CLOUD_NODE = "/camera/cloud"


class CloudLayer(Layer):
    """The newest rendered point cloud, in the base frame; frames without one keep the last."""

    cue = None

    def __init__(self, scene: viser.SceneApi, point_size_m: float) -> None:
        super().__init__()
        self._scene = scene
        self._point_size_m = point_size_m
        self._handle: viser.PointCloudHandle | None = None

    def update(self, frame: DisplayFrame) -> None:
        if frame.cloud_points_m is None or frame.cloud_colors is None:
            return
        self._handle = self._scene.add_point_cloud(
            CLOUD_NODE,
            frame.cloud_points_m,
            frame.cloud_colors,
            point_size=self._point_size_m,
            precision="float32",
            visible=bool(self._visible),
        )

    def _set_visible(self, visible: bool) -> None:
        if self._handle is not None:
            self._handle.visible = visible

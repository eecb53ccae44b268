"""The head camera's point cloud: the remote scene itself, drawn under every modality."""

from __future__ import annotations

import numpy as np
import viser

from arteleop.ar_features.display_frame import DisplayFrame
from arteleop.ar_features.layer import Layer

CLOUD_NODE = "/camera/cloud"
BAND_RATIO = 1.25
"""The cloud is drawn in bands of distance from the camera, each this many times farther than
the one before, with its points' size: viser draws one size per cloud, and a point's footprint
grows with its distance, so a point is at most this much wider than its own footprint needs."""


class CloudLayer(Layer):
    """The newest rendered point cloud, in the base frame; frames without one keep the last.

    Each point is drawn as wide as its pixel's footprint at its distance (the angle between
    neighbouring points of the displayed cloud times that distance, the band's farthest), times
    ``overlap``: seen from the head camera, where the view starts, neighbours touch and the
    surfaces read as surfaces, at any resolution and decimation.
    """

    cue = None

    def __init__(self, scene: viser.SceneApi, overlap: float) -> None:
        super().__init__()
        self._scene = scene
        self._overlap = overlap
        self._handles: dict[str, viser.PointCloudHandle] = {}

    def update(self, frame: DisplayFrame) -> None:
        points, colors, spacing = frame.cloud_points_m, frame.cloud_colors, frame.cloud_spacing_rad
        if points is None or colors is None or spacing is None:
            return
        eye = frame.T_base_camera[:3, 3].astype(np.float32)
        distance = np.maximum(np.linalg.norm(points - eye, axis=1), 1e-3)
        near_m = float(distance.min()) if len(distance) else 1.0
        band = np.floor(np.log(distance / near_m) / np.log(BAND_RATIO))
        handles = {}
        for k in np.unique(band).astype(int):
            name = f"{CLOUD_NODE}/{k}"
            inside = band == k
            far_m = near_m * BAND_RATIO ** (k + 1.0)
            handles[name] = self._scene.add_point_cloud(
                name, points[inside], colors[inside],
                point_size=self._overlap * spacing * far_m, precision="float32",
                visible=bool(self._visible),
            )  # fmt: skip
        for name, handle in self._handles.items():
            if name not in handles:  # a band this frame has no points in
                handle.remove()
        self._handles = handles

    def _set_visible(self, visible: bool) -> None:
        for handle in self._handles.values():
            handle.visible = visible

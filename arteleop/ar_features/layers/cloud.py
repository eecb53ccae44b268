"""The head camera's point cloud: the remote scene itself, drawn under every modality."""

from __future__ import annotations

import itertools

import numpy as np
import viser

from arteleop.ar_features.display_frame import DisplayFrame
from arteleop.ar_features.layer import Layer

CLOUD_NODE = "/camera/cloud"
BAND_RATIO = 1.25
"""The cloud is drawn in bands of distance from the camera, band k spanning
``BAND_RATIO**k`` to ``BAND_RATIO**(k + 1)`` metres, each with its points' size: viser draws one
size per cloud, and a point's footprint grows with its distance, so a point is at most this much
wider than its own footprint needs."""


class CloudLayer(Layer):
    """The newest rendered point cloud, in the base frame; frames without one keep the last.

    Each point is drawn as wide as its pixel's footprint at its distance (the angle between
    neighbouring points of the displayed cloud times that distance, its band's farthest), times
    ``overlap``: seen from the head camera, where the view starts, neighbours touch and the
    surfaces read as surfaces, at any resolution and decimation.

    The bands lie at fixed distances, so a band's node outlives the frame: each frame replaces
    its points and colours. A new node per band and frame cost viser about 1 ms each (4-5 a
    frame), a third of a 640x480 frame's time on the display.
    """

    cue = None

    def __init__(self, server: viser.ViserServer, overlap: float) -> None:
        super().__init__()
        self._server = server
        self._overlap = overlap
        self._handles: dict[int, viser.PointCloudHandle] = {}

    def update(self, frame: DisplayFrame) -> None:
        points, colors, spacing = frame.cloud_points_m, frame.cloud_colors, frame.cloud_spacing_rad
        if points is None or colors is None or spacing is None:
            return
        offset = points - frame.T_base_camera[:3, 3].astype(points.dtype)
        distance = np.sqrt(np.einsum("ij,ij->i", offset, offset))
        np.maximum(distance, 1e-3, out=distance)
        # Sorted by band (a radix sort on 16-bit keys), each band is one slice.
        band = np.floor(np.log(distance) / np.log(BAND_RATIO)).astype(np.int16)
        order = np.argsort(band, kind="stable")
        points, colors = points[order], colors[order]
        lowest = int(band.min()) if len(band) else 0
        bounds = [0, *np.cumsum(np.bincount(band - lowest)).tolist()] if len(band) else [0]
        present = set()
        with self._server.atomic():  # a browser applies a band's points and colours together
            for i, (start, end) in enumerate(itertools.pairwise(bounds)):
                if end == start:
                    continue
                k = lowest + i
                present.add(k)
                size = self._overlap * spacing * BAND_RATIO ** (k + 1.0)
                handle = self._handles.get(k)
                if handle is None:
                    self._handles[k] = self._server.scene.add_point_cloud(
                        f"{CLOUD_NODE}/{k}", points[start:end], colors[start:end],
                        point_size=size, precision="float32", visible=bool(self._visible),
                    )  # fmt: skip
                    continue
                handle.points = points[start:end]
                handle.colors = colors[start:end]
                handle.point_size = size  # sent only when it changes (another camera)
            for k in set(self._handles) - present:  # bands this frame has no points in
                self._handles.pop(k).remove()

    def _set_visible(self, visible: bool) -> None:
        for handle in self._handles.values():
            handle.visible = visible

"""The head camera's point cloud: the remote scene itself, drawn under every modality.

A frame's cloud is most of what the view sends a browser (680 kB a frame at 640x480, thinned by
two: 80 Mbit/s at 15 frames a second), and most of it does not change from frame to frame: the
table, the markers, the arm at rest. So the cloud is drawn in tiles of the camera image, each
its own node, and a frame sends only the tiles whose content has changed since they were last
sent: points that moved by more than the depth sensor's noise and quantisation move one
(:data:`MOVED_AT_1M_M`, growing with the square of the distance as they do), changed colour, or
appeared or went (the arm passing, the bowl carried, a hole where the arm is too near the
camera), in more than :data:`CHANGED_SHARE` of a tile's points; and each frame the few tiles
with the most changes too small for that (:data:`REFRESHED_TILES`), so that no stray piece of a
thing gone stays. A still tile keeps the noise of the frame it was sent in. A thing moved
sideways changes the pixels along its edges, from it to what lies behind: a gripper stepped
1 cm at the table changes about a tenth of its tile's points. Positions go as 16-bit floats
relative to the tile's corner, finer than a millimetre.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import viser
from numpy.typing import NDArray

from arteleop.ar_features.display_frame import DisplayFrame
from arteleop.ar_features.layer import Layer

CLOUD_NODE = "/camera/cloud"
POINT_BYTES = 9
"""A point's bytes as sent: three 16-bit floats and three 8-bit colours."""
TILES = (16, 12)
"""Tiles across and down the camera image: at 640x480 thinned by two, 20 x 20 points each."""
MOVED_AT_1M_M = 0.008
"""A point at 1 m from the camera moved further than this since its tile was sent has changed
(m); at z metres, ``z**2`` times this. Between two frames of a still scene, one point in a
thousand moves 10.5 mm at 0.9-1.2 m, 12.3 mm at 1.2-1.5 m and 13.5 mm at 1.5-1.8 m (the
Kinect's noise and its disparity steps, both growing with ``z**2``); this is 12-15 mm at the
table's near half and 26 mm at its far edge."""
COLOR_STEP = 32
"""A point whose colour changed by more than this in a channel (of 255) has changed: the camera
adds no noise to colours, and a thing passing changes them by far more."""
CHANGED_SHARE = 0.02
"""A tile is sent again when more than this share of its points moved, came or went."""
REFRESHED_TILES = 4
"""Tiles sent each frame besides those changed, of those with changes too few to count: the
most changed first."""
FAR_QUANTILE = 0.98
"""A tile's points are drawn as wide as a point's footprint at this quantile of their distances
(viser draws one size per cloud): the farthest but for a stray few."""


@dataclass
class _Sent:
    """A tile as last sent: its points' image keys (sorted), positions, colours and distances
    from the camera (m)."""

    keys: NDArray[np.int64]
    points_m: NDArray[np.float32]
    colors: NDArray[np.uint8]
    distance_m: NDArray[np.float32]


class CloudLayer(Layer):
    """The newest rendered point cloud, in the base frame; frames without one keep the last.

    Each point is drawn as wide as its pixel's footprint at its distance (the angle between
    neighbouring points of the displayed cloud times that distance, its tile's farthest), times
    ``overlap``: seen from the head camera, where the view starts, neighbours touch and the
    surfaces read as surfaces, at any resolution and decimation. ``half_fov_tan`` is the
    tangents of the camera's half fields of view (horizontal, vertical): where the tiles lie.
    """

    cue = None

    def __init__(
        self, server: viser.ViserServer, overlap: float, half_fov_tan: tuple[float, float]
    ) -> None:
        super().__init__()
        self._server = server
        self._overlap = overlap
        self._half_fov_tan = np.asarray(half_fov_tan, dtype=np.float32)
        self._handles: dict[int, viser.PointCloudHandle] = {}
        self._sent: dict[int, _Sent] = {}
        self.tiles_sent = 0
        """Tiles sent so far, over every frame."""
        self.frames_drawn = 0
        """Frames with a cloud drawn so far."""
        self.interval = 1
        """Camera frames between two clouds drawn (1: every frame): a slow connection's pace
        (:class:`~arteleop.ar_features.link_pacer.LinkPacer`). A frame passed over sends
        nothing; the next drawn sends what changed since the last drawn."""
        self.frames_held = 0
        """Frames with a cloud passed over at that pace so far."""
        self._offered = 0
        self._latest: DisplayFrame | None = None
        self.payload_bytes = 0
        """The points' positions and colours sent so far (bytes): what a browser receives,
        before compression and besides the messages' own few bytes."""

    def update(self, frame: DisplayFrame) -> None:
        if (
            frame.cloud_points_m is None
            or frame.cloud_colors is None
            or frame.cloud_spacing_rad is None
        ):
            return
        self._latest = frame
        self._offered += 1
        if self._offered % self.interval:
            self.frames_held += 1
            return
        self.frames_drawn += 1
        self._draw_tiles(frame, every_change=False)

    def settle(self) -> None:
        """Send every tile the latest frame changed at all, now: for a frame that no other
        follows soon (a trial's scene while a person gets ready, a trial's last), whose small
        changes, and a held frame's, would otherwise stay off the screen: a tile where a new
        scene differs by a point or two kept the old scene's points until Start."""
        if self._latest is not None:
            self._draw_tiles(self._latest, every_change=True)

    def _draw_tiles(self, frame: DisplayFrame, every_change: bool) -> None:
        """Send the tiles of ``frame`` that changed (beyond :data:`CHANGED_SHARE`, and
        :data:`REFRESHED_TILES` of the others; with ``every_change``, every tile changed)."""
        points, colors, spacing = frame.cloud_points_m, frame.cloud_colors, frame.cloud_spacing_rad
        assert points is not None and colors is not None and spacing is not None
        tile, keys, distance = self._place(frame, points, spacing)
        order = np.lexsort((keys, tile))  # by tile, then by pixel
        points, colors, tile, keys, distance = (
            points[order], colors[order], tile[order], keys[order], distance[order]
        )  # fmt: skip
        count = int(np.prod(TILES))
        bounds = np.searchsorted(tile, np.arange(count + 1))
        tiles, lagging = [], []
        for k in range(count):
            start, end = int(bounds[k]), int(bounds[k + 1])
            new = _Sent(keys[start:end], points[start:end], colors[start:end],
                        distance[start:end])  # fmt: skip
            last = self._sent.get(k)
            if last is None:
                if end > start:
                    tiles.append((k, new))
                continue
            changed = _changed_points(last, new)
            if changed > CHANGED_SHARE * max(len(last.keys), len(new.keys)):
                tiles.append((k, new))
            elif changed:
                lagging.append((changed, k, new))
        # A few changes too small to send a tile for (a stray edge of the bowl carried away)
        # would stay: the tiles with the most go too, a few a frame.
        lagging.sort(key=lambda item: -item[0])
        tiles += [(k, new) for _, k, new in lagging[: None if every_change else REFRESHED_TILES]]
        with self._server.atomic():  # a browser applies a tile's points and colours together
            for k, new in tiles:
                self._send(k, new, spacing)

    def _place(
        self, frame: DisplayFrame, points: NDArray[np.float32], spacing: float
    ) -> tuple[NDArray[np.int64], NDArray[np.int64], NDArray[np.float32]]:
        """Each point's tile, its pixel's key (the same pixel gives the same key in every frame)
        and its distance from the camera (m)."""
        camera = (points - frame.T_base_camera[:3, 3]) @ frame.T_base_camera[:3, :3]
        depth = np.maximum(camera[:, 2], 1e-3)
        # A pixel's ray, whatever its depth: where it lies in the image, in units of the
        # cloud's spacing. Every pixel lies the same fraction of a unit off the whole numbers
        # (the image's centre, thinned): taken off, a pixel is a pair of whole numbers.
        ray = camera[:, :2] / depth[:, None]
        steps = ray / spacing
        # (Where that fraction is a half, an image W px wide, W = 3 mod 4, thinned by two,
        # the rounding may take either side from frame to frame: every tile is then sent.)
        offset = steps[0] - np.rint(steps[0]) if len(steps) else 0.0
        grid = np.rint(steps - offset).astype(np.int64)
        keys = grid[:, 1] * 100_000 + grid[:, 0]
        cells = np.asarray(TILES)
        at = np.floor((ray / self._half_fov_tan + 1) / 2 * cells).astype(np.int64)
        at = np.clip(at, 0, cells - 1)
        distance = np.sqrt(np.einsum("ij,ij->i", camera, camera)).astype(np.float32)
        return at[:, 1] * TILES[0] + at[:, 0], keys, distance

    def _send(self, k: int, tile: _Sent, spacing: float) -> None:
        # Copies: slices would keep the whole frame they came from alive, tile by tile.
        tile = _Sent(tile.keys.copy(), tile.points_m.copy(), tile.colors.copy(),
                     tile.distance_m.copy())  # fmt: skip
        self._sent[k] = tile
        self.tiles_sent += 1
        self.payload_bytes += POINT_BYTES * len(tile.keys)
        handle = self._handles.get(k)
        if len(tile.keys) == 0:
            if handle is not None:
                handle.points = np.zeros((0, 3), np.float16)
                handle.colors = np.zeros((0, 3), np.uint8)
            return
        corner = np.floor(tile.points_m.min(axis=0) * 100) / 100  # a centimetre grid
        relative = (tile.points_m - corner).astype(np.float16)
        size = self._overlap * spacing * float(np.quantile(tile.distance_m, FAR_QUANTILE))
        if handle is None:
            self._handles[k] = self._server.scene.add_point_cloud(
                f"{CLOUD_NODE}/{k}", relative, tile.colors, point_size=size,
                precision="float16", position=tuple(corner.tolist()),
                visible=bool(self._visible),
            )  # fmt: skip
            return
        handle.position = tuple(corner.tolist())
        handle.points = relative
        handle.colors = tile.colors
        handle.point_size = size

    def _set_visible(self, visible: bool) -> None:
        for handle in self._handles.values():
            handle.visible = visible


def _changed_points(last: _Sent, new: _Sent) -> int:
    """How many of a tile's points moved further than :data:`MOVED_AT_1M_M` at their distance,
    changed colour by more than :data:`COLOR_STEP`, came or went since ``last``."""
    _, i, j = np.intersect1d(last.keys, new.keys, return_indices=True)
    moved = last.points_m[i] - new.points_m[j]
    limit = MOVED_AT_1M_M * last.distance_m[i] ** 2
    far = np.einsum("ij,ij->i", moved, moved) > limit**2
    recoloured = np.abs(last.colors[i].astype(np.int16) - new.colors[j]).max(axis=1) > COLOR_STEP
    return int(np.count_nonzero(far | recoloured)) + len(last.keys) + len(new.keys) - 2 * len(i)

"""MeshReconstructor: a triangle mesh from the depth grid (docs/explanation/study.md §7).

Neighbouring pixels become triangles. Small holes in the depth image are filled by
inpainting; triangles whose corners differ in depth by more than a threshold are dropped,
because they would join surfaces that are far apart (an arm in front of the table). Depth can be
averaged over the last N frames against noise.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass
from typing import TYPE_CHECKING

import cv2
import numpy as np
from numpy.typing import NDArray

from arteleop.errors import ConfigurationError
from arteleop.scene.camera import RGBDFrame
from arteleop.scene.pointcloud import depth_to_camera_points
from arteleop.transforms import transform_points

if TYPE_CHECKING:
    import open3d as o3d


@dataclass(frozen=True)
class MeshReconstructorConfig:
    """Settings of the depth-grid mesher.

    Attributes:
        stride: Use every stride-th pixel as a vertex (1 = full resolution).
        max_hole_px: Invalid regions of at most this many pixels are filled by inpainting.
        max_depth_jump_ratio: Drop a triangle when its corners' depths differ by more than this
            fraction of their mean depth (0.05 = 5 cm at 1 m).
        average_frames: Average each pixel's depth over the last N frames in which it was valid.
    """

    stride: int = 2
    max_hole_px: int = 64
    max_depth_jump_ratio: float = 0.05
    average_frames: int = 1

    def __post_init__(self) -> None:
        if self.stride < 1 or self.average_frames < 1 or self.max_hole_px < 0:
            raise ConfigurationError(
                f"MeshReconstructorConfig: stride ({self.stride}) and average_frames "
                f"({self.average_frames}) must be >= 1 and max_hole_px ({self.max_hole_px}) >= 0"
            )
        if self.max_depth_jump_ratio <= 0:
            raise ConfigurationError(
                f"max_depth_jump_ratio must be > 0, got {self.max_depth_jump_ratio}"
            )


@dataclass(frozen=True)
class DepthMesh:
    """Vertices (N, 3) in the base frame (m), triangles (M, 3), vertex colours (N, 3) uint8."""

    vertices_m: NDArray[np.float64]
    triangles: NDArray[np.int32]
    colors: NDArray[np.uint8]

    def to_open3d(self) -> o3d.geometry.TriangleMesh:
        import open3d as o3d  # 1.7 s to import (dash, IPython): only when asked for

        mesh = o3d.geometry.TriangleMesh(
            o3d.utility.Vector3dVector(self.vertices_m), o3d.utility.Vector3iVector(self.triangles)
        )
        mesh.vertex_colors = o3d.utility.Vector3dVector(self.colors / 255.0)
        return mesh


class MeshReconstructor:
    """Turns successive RGB-D frames into triangle meshes of the visible surfaces."""

    def __init__(self, config: MeshReconstructorConfig | None = None) -> None:
        self.config = config or MeshReconstructorConfig()
        self._history: deque[NDArray[np.float32]] = deque(maxlen=self.config.average_frames)

    def reset(self) -> None:
        """Forget the frames kept for averaging."""
        self._history.clear()

    def averaged_depth(self, depth_m: NDArray[np.float32]) -> NDArray[np.float32]:
        """Add a depth frame to the history; return the per-pixel mean over valid samples."""
        if self._history and self._history[0].shape != depth_m.shape:
            self._history.clear()
        self._history.append(depth_m)
        stack = np.stack(self._history)
        count = (stack > 0).sum(axis=0)
        mean = stack.sum(axis=0) / np.maximum(count, 1)
        return np.where(count > 0, mean, 0.0).astype(np.float32)

    def fill_holes(self, depth_m: NDArray[np.float32]) -> NDArray[np.float32]:
        """Inpaint invalid regions of at most ``max_hole_px`` pixels; leave larger ones empty."""
        invalid = (depth_m <= 0).astype(np.uint8)
        n, labels, stats, _ = cv2.connectedComponentsWithStats(invalid, connectivity=4)
        small = np.zeros(n, dtype=bool)
        small[1:] = stats[1:, cv2.CC_STAT_AREA] <= self.config.max_hole_px
        mask = small[labels] & (invalid > 0)
        if not mask.any():
            return depth_m
        filled = cv2.inpaint(depth_m.astype(np.float32), mask.astype(np.uint8), 3, cv2.INPAINT_NS)
        return np.where(mask, filled, depth_m).astype(np.float32)

    def reconstruct(self, frame: RGBDFrame) -> DepthMesh:
        """Mesh of ``frame`` (after averaging and hole filling), in the base frame."""
        c = self.config
        depth = self.fill_holes(self.averaged_depth(frame.depth_m))[:: c.stride, :: c.stride]
        grid = depth_to_camera_points(depth, frame.intrinsics.strided(c.stride))
        h, w = depth.shape
        idx = np.arange(h * w).reshape(h, w)
        a, b = idx[:-1, :-1].ravel(), idx[:-1, 1:].ravel()
        cc, d = idx[1:, :-1].ravel(), idx[1:, 1:].ravel()
        tris = np.concatenate([np.column_stack([a, cc, b]), np.column_stack([b, cc, d])])
        z = depth.ravel()[tris]  # (M, 3)
        keep = (z > 0).all(axis=1)
        zmax, zmin = z.max(axis=1), z.min(axis=1)
        keep &= (zmax - zmin) <= c.max_depth_jump_ratio * 0.5 * (zmax + zmin)
        tris = tris[keep]
        used = np.unique(tris)
        remap = np.full(h * w, -1, dtype=np.int64)
        remap[used] = np.arange(len(used))
        vertices = transform_points(frame.T_base_camera, grid.reshape(-1, 3)[used])
        colors = frame.rgb[:: c.stride, :: c.stride].reshape(-1, 3)[used]
        return DepthMesh(vertices, remap[tris].astype(np.int32), colors)

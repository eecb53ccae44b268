"""From RGB-D frames to coloured point clouds in Baxter's base frame."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from arteleop.scene.camera import RGBDFrame
from arteleop.scene.camera_config import CameraIntrinsics
from arteleop.transforms import transform_points

if TYPE_CHECKING:
    import open3d as o3d


@dataclass(frozen=True)
class PointCloud:
    """Points (N, 3) in metres in the base frame, with (N, 3) uint8 colours and their pixels.

    ``pixels`` (N, 2) holds each point's (row, column) in the frame it came from;
    ``spacing_rad`` the angle between neighbouring points as the camera saw them (a pixel's
    angle at the image centre times the stride, rad): a point's footprint is this times its
    distance from the camera.
    """

    points_m: NDArray[np.float64]
    colors: NDArray[np.uint8]
    pixels: NDArray[np.int64]
    spacing_rad: float

    def to_open3d(self) -> o3d.geometry.PointCloud:
        import open3d as o3d  # 1.7 s to import (dash, IPython): only when asked for

        cloud = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(self.points_m))
        cloud.colors = o3d.utility.Vector3dVector(self.colors.astype(np.float64) / 255.0)
        return cloud


def depth_to_camera_points(
    depth_m: NDArray[np.floating], K: CameraIntrinsics
) -> NDArray[np.float64]:
    """Back-project a depth image to an (H, W, 3) grid of camera-frame points (m)."""
    h, w = depth_m.shape
    z = depth_m.astype(np.float64)
    u = np.arange(w, dtype=np.float64)[None, :]
    v = np.arange(h, dtype=np.float64)[:, None]
    return np.stack([(u - K.cx_px) / K.fx_px * z, (v - K.cy_px) / K.fy_px * z, z], axis=-1)


def frame_to_point_cloud(
    frame: RGBDFrame, stride: int = 1, T_base_camera: NDArray[np.float64] | None = None
) -> PointCloud:
    """Coloured point cloud of the valid pixels of ``frame``, in the base frame.

    ``stride`` keeps every stride-th row and column, to thin the cloud for display.
    ``T_base_camera`` places it (4x4, m); by default the pose the frame was stamped with.
    """
    depth = frame.depth_m[::stride, ::stride]
    rows, cols = np.nonzero(depth > 0)
    # depth_to_camera_points' arithmetic on the valid pixels alone (same numbers, a third of
    # the work at 640x480, where the cloud is built 30 times a second).
    K = frame.intrinsics.strided(stride)
    z = depth[rows, cols].astype(np.float64)
    camera = np.column_stack(
        [(cols.astype(np.float64) - K.cx_px) / K.fx_px * z,
         (rows.astype(np.float64) - K.cy_px) / K.fy_px * z, z]
    )  # fmt: skip
    T = frame.T_base_camera if T_base_camera is None else T_base_camera
    points = transform_points(T, camera)
    colors = frame.rgb[::stride, ::stride][rows, cols]
    pixels = np.column_stack([rows * stride, cols * stride])
    return PointCloud(points, colors, pixels, stride / frame.intrinsics.fx_px)

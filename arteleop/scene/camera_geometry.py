"""Where the head camera is and what it can see: plain geometry, no renderer.

The loop asks it whether a point (the gripper, the bowl) is in the image and in the sensor's
depth range, from the camera's pose and its configuration alone.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from arteleop.scene.camera_config import CameraIntrinsics, HeadCameraConfig
from arteleop.transforms import invert_transform, transform_points

LANDMARK_MARGIN_FRACTION = 10 / 640
"""How far inside the image's edge the task's landmarks must project, as a fraction of the
image's width (:func:`landmark_problem`): 10 px of the Kinect's 640, the same angle at any
resolution."""


@dataclass(frozen=True)
class CameraGeometry:
    """The head camera's pose and its image and depth limits.

    Attributes:
        config: Image size, field of view and depth range.
        T_base_camera: Pose of the optical frame (x right, y down, z forward) in the base frame.
    """

    config: HeadCameraConfig
    T_base_camera: NDArray[np.float64]
    _T_camera_base: NDArray[np.float64] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        T = np.array(self.T_base_camera, dtype=np.float64)
        T.setflags(write=False)
        object.__setattr__(self, "T_base_camera", T)
        object.__setattr__(self, "_T_camera_base", invert_transform(T))

    @property
    def intrinsics(self) -> CameraIntrinsics:
        return self.config.intrinsics

    @property
    def position_m(self) -> NDArray[np.float64]:
        """The optical centre in the base frame (m)."""
        return self.T_base_camera[:3, 3]

    def locate(self, point_base_m: ArrayLike) -> tuple[float, float, float]:
        """Pixel (u, v) and depth z (m) of a base-frame point; u and v are nan behind the camera."""
        pc = transform_points(self._T_camera_base, np.atleast_2d(point_base_m))[0]
        if pc[2] <= 0:
            return math.nan, math.nan, float(pc[2])
        u, v = self.intrinsics.project(pc)[0]
        return float(u), float(v), float(pc[2])

    def sees(self, point_base_m: ArrayLike, margin_px: float = 0.0) -> bool:
        """Whether a base-frame point is in the image (with a margin) and in the depth range."""
        return bool(self.sees_points(np.atleast_2d(point_base_m), margin_px)[0])

    def sees_points(self, points_base_m: ArrayLike, margin_px: float = 0.0) -> NDArray[np.bool_]:
        """:meth:`sees` for each of (N, 3) base-frame points: (N,) booleans."""
        pc = transform_points(self._T_camera_base, np.asarray(points_base_m, dtype=np.float64))
        c = self.config
        z = pc[:, 2]
        in_range = (c.min_depth_m <= z) & (z <= c.max_depth_m)
        uv = np.full((len(pc), 2), -1.0)
        uv[in_range] = self.intrinsics.project(pc[in_range])
        return (
            in_range
            & (margin_px <= uv[:, 0]) & (uv[:, 0] <= c.width_px - 1 - margin_px)
            & (margin_px <= uv[:, 1]) & (uv[:, 1] <= c.height_px - 1 - margin_px)
        )  # fmt: skip


def landmark_problem(geometry: CameraGeometry, landmarks_m: Mapping[str, ArrayLike]) -> str | None:
    """Why the camera cannot see the first of the named base-frame points (m) that it misses
    (out of its depth range, or projecting outside the image less
    :data:`LANDMARK_MARGIN_FRACTION`), in words naming the point; None when it sees them all."""
    c = geometry.config
    margin_px = LANDMARK_MARGIN_FRACTION * c.width_px
    for name, point in landmarks_m.items():
        if geometry.sees(point, margin_px):
            continue
        u, v, z = geometry.locate(point)
        where = f"The head camera can't see the {name} at {np.round(point, 3).tolist()} m"
        if not c.min_depth_m <= z <= c.max_depth_m:
            return (
                f"{where}: it lies {z:.2f} m along the optical axis, outside the depth range "
                f"[{c.min_depth_m}, {c.max_depth_m}] m"
            )
        return (
            f"{where}: it projects to pixel ({u:.0f}, {v:.0f}), outside the "
            f"{c.width_px}x{c.height_px} image (less {margin_px:.3g} px at its edges)"
        )
    return None


def colocation_errors(
    T_base_camera_true: NDArray[np.float64],
    T_base_camera_registered: NDArray[np.float64],
    intrinsics: CameraIntrinsics,
    points_base_m: ArrayLike,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """How far a virtual object drawn at each of (N, 3) base-frame points lands from the real
    one seen by the camera, when the system places the camera's view with the registered pose
    (4x4, m) instead of the true one: (N,) distances in the image (px) and (N,) in the camera's
    frame (m)."""
    points = np.asarray(points_base_m, dtype=np.float64).reshape(-1, 3)
    real = transform_points(invert_transform(T_base_camera_true), points)
    drawn = transform_points(invert_transform(T_base_camera_registered), points)
    px = np.linalg.norm(intrinsics.project(drawn) - intrinsics.project(real), axis=1)
    return px, np.linalg.norm(drawn - real, axis=1)

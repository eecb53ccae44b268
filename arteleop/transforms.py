"""Homogeneous transforms and quaternion conventions shared by every subpackage.

Conventions (see docs/explanation/architecture.md, "Conventions"):
- ``T_a_b`` is a 4x4 homogeneous matrix that maps coordinates in frame b to frame a,
  i.e. the pose of frame b expressed in frame a. ``T_a_c = T_a_b @ T_b_c``.
- Quaternions are ``(w, x, y, z)`` in the API. PyBullet uses ``(x, y, z, w)``: convert with
  :func:`quat_xyzw_to_wxyz` / :func:`quat_wxyz_to_xyzw` at that boundary only.
"""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin
from numpy.typing import ArrayLike, NDArray
from scipy.spatial.transform import Rotation


def quat_xyzw_to_wxyz(q_xyzw: ArrayLike) -> NDArray[np.float64]:
    """Reorder a PyBullet quaternion (x, y, z, w) into the API's (w, x, y, z)."""
    q = np.asarray(q_xyzw, dtype=np.float64)
    return np.concatenate([q[..., 3:], q[..., :3]], axis=-1)


def quat_wxyz_to_xyzw(q_wxyz: ArrayLike) -> NDArray[np.float64]:
    """Reorder an API quaternion (w, x, y, z) into PyBullet's (x, y, z, w)."""
    q = np.asarray(q_wxyz, dtype=np.float64)
    return np.concatenate([q[..., 1:], q[..., :1]], axis=-1)


def make_transform(rotation: ArrayLike, translation_m: ArrayLike) -> NDArray[np.float64]:
    """Build a 4x4 transform from a 3x3 rotation matrix and a translation in metres."""
    T = np.eye(4)
    T[:3, :3] = np.asarray(rotation, dtype=np.float64)
    T[:3, 3] = np.asarray(translation_m, dtype=np.float64)
    return T


def quat_to_matrix(quat_wxyz: ArrayLike) -> NDArray[np.float64]:
    """3x3 rotation matrix of one (w, x, y, z) quaternion, normalised first.

    pinocchio does it in C++: per call about a tenth of scipy's ``Rotation`` (which pays for
    its batch machinery on every call), and this runs at the control rate.
    """
    w, x, y, z = np.asarray(quat_wxyz, dtype=np.float64)
    return pin.Quaternion(w, x, y, z).normalized().toRotationMatrix()


_FEW = 16
"""Up to this many rotations are converted one by one in pinocchio (about 4 us each), more in
one scipy call, which costs 30-60 us in its input checks before it starts: a control tick
converts three rotations at a time, a recording thousands."""


def quats_to_matrices(quat_wxyz: ArrayLike) -> NDArray[np.float64]:
    """Rotation matrices (..., 3, 3) of (w, x, y, z) quaternions (..., 4), normalised first."""
    q = np.asarray(quat_wxyz, dtype=np.float64)
    flat = q.reshape(-1, 4)
    if len(flat) <= _FEW:
        R = np.array([quat_to_matrix(row) for row in flat]).reshape(-1, 3, 3)
    else:
        R = Rotation.from_quat(flat, scalar_first=True).as_matrix()
    return R.reshape(q.shape[:-1] + (3, 3))


def matrices_to_quats(R: ArrayLike) -> NDArray[np.float64]:
    """(w, x, y, z) quaternions (..., 4) of rotation matrices (..., 3, 3), with w >= 0."""
    R = np.asarray(R, dtype=np.float64)
    flat = R.reshape(-1, 3, 3)
    if len(flat) <= _FEW:
        q = np.empty((len(flat), 4))
        for i, m in enumerate(flat):
            c = pin.Quaternion(m)
            w, x, y, z = c.w, c.x, c.y, c.z
            scale = math.copysign(1.0 / math.sqrt(w * w + x * x + y * y + z * z), w)
            q[i] = (w * scale, x * scale, y * scale, z * scale)
    else:
        q = Rotation.from_matrix(flat).as_quat(scalar_first=True, canonical=True)
    return q.reshape(R.shape[:-2] + (4,))


def rotvecs_to_matrices(rotvec_rad: ArrayLike) -> NDArray[np.float64]:
    """Rotation matrices (..., 3, 3) of rotation vectors (..., 3): axis times angle (rad)."""
    v = np.asarray(rotvec_rad, dtype=np.float64)
    flat = v.reshape(-1, 3)
    if len(flat) <= _FEW:
        R = np.array([pin.exp3(row) for row in flat]).reshape(-1, 3, 3)
    else:
        R = Rotation.from_rotvec(flat).as_matrix()
    return R.reshape(v.shape[:-1] + (3, 3))


def rotations_z(angle_rad: ArrayLike) -> NDArray[np.float64]:
    """Rotation matrices (..., 3, 3) about z by ``angle_rad`` (...,)."""
    a = np.asarray(angle_rad, dtype=np.float64)
    c, s = np.cos(a), np.sin(a)
    R = np.zeros(a.shape + (3, 3))
    R[..., 0, 0] = c
    R[..., 0, 1] = -s
    R[..., 1, 0] = s
    R[..., 1, 1] = c
    R[..., 2, 2] = 1.0
    return R


def pybullet_pose_to_transform(
    position_m: tuple[float, float, float], quat_xyzw: tuple[float, float, float, float]
) -> NDArray[np.float64]:
    """``T_parent_child`` from a pose as PyBullet returns it (its quaternion is (x, y, z, w),
    unit length): the boundary conversion, on the site's per-tick path, in plain arithmetic
    (a fifth of converting the quaternion and building the matrix through numpy)."""
    x, y, z, w = quat_xyzw
    px, py, pz = position_m
    return np.array(
        (
            (1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w), px),
            (2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w), py),
            (2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y), pz),
            (0.0, 0.0, 0.0, 1.0),
        )
    )


def pose_to_transform(position_m: ArrayLike, quat_wxyz: ArrayLike) -> NDArray[np.float64]:
    """Build ``T_parent_child`` from a position (m) and a (w, x, y, z) quaternion."""
    return make_transform(quat_to_matrix(quat_wxyz), position_m)


def transform_to_pose(T: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Split a 4x4 transform into (position in m, (w, x, y, z) quaternion with w >= 0)."""
    T = np.asarray(T, dtype=np.float64)
    return T[:3, 3].copy(), matrices_to_quats(T[:3, :3])


def invert_transform(T: ArrayLike) -> NDArray[np.float64]:
    """Inverse of a rigid transform: ``T_b_a`` from ``T_a_b``."""
    T = np.asarray(T, dtype=np.float64)
    R = T[:3, :3]
    return make_transform(R.T, -R.T @ T[:3, 3])


def transform_points(T_a_b: ArrayLike, points_b: ArrayLike) -> NDArray[np.float64]:
    """Map points of shape (N, 3) from frame b to frame a."""
    T = np.asarray(T_a_b, dtype=np.float64)
    p = np.asarray(points_b, dtype=np.float64)
    return p @ T[:3, :3].T + T[:3, 3]


def sight_is_vertical(T_base_camera: ArrayLike) -> bool:
    """Whether a camera's optical axis (the z column of ``T_base_camera``'s rotation, 3x3 or
    4x4; base z up) is within 2.6 deg of the vertical: its line of sight gives no direction on
    the table, nor a vertical to keep its view's up by, and its own image's up stands in."""
    forward = np.asarray(T_base_camera, dtype=np.float64)[:3, 2]
    return bool(abs(forward[2]) > 0.999)

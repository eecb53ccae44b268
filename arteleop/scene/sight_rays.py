"""Rays from the head camera into the simulated world: what the camera would see of a point,
without rendering a frame (the bowl's and the marks' sight models)."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from arteleop.robot.bullet_client import KeptBulletClient

RAY_OVERSHOOT_M = 0.02
"""The rays run this far past their surface point (m): a ray that ends at the drawn surface may
stop short of the collision shape, which stands off it by a few millimetres."""


def first_hits(
    client: KeptBulletClient, eye_m: NDArray[np.float64], points_m: NDArray[np.float64]
) -> NDArray[np.float64]:
    """Where the rays from ``eye_m`` to (N, 3) points first hit anything in ``client``'s world
    (N, 3; nan: no hit), base frame, m."""
    rays = points_m - eye_m
    ends = points_m + RAY_OVERSHOOT_M * rays / np.linalg.norm(rays, axis=1, keepdims=True)
    results = client.rayTestBatch([eye_m.tolist()] * len(points_m), ends.tolist())
    return np.array([r[3] if r[0] >= 0 else (np.nan,) * 3 for r in results])

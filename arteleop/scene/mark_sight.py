"""How much of the marks on the table the point cloud draws, for camera frames that are not
rendered.

The target circle and the start cross are drawn on the table; the cloud shows them where the
head camera sees the table there: in its image and depth range, and not behind the arm, the
gripper or the bowl (the arm near the camera is closer than the sensor's range and so is not in
the cloud, but it still hides the table behind it). As for the bowl
(:mod:`arteleop.scene.bowl_sight`), the site casts a ray from the camera to points along each
mark's line and counts those whose first hit is the table at that point.

Against rendered frames (``tests/scene/test_bowl_sight.py``) the target circle's share agrees to
a point in 24 but where an edge passes over it. The start cross lies behind the right shoulder
from the camera, and the shoulder's drawn mesh is wider than its collision mesh, which is all a
ray meets: with the arm reaching, the model draws up to the whole cross where the frame hides
most of it (6 % of the cross's points on average over three seeded trials). It hides what the
frame draws only where an edge passes over the cross (3 of its 24 points, in one look of 139).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from arteleop.scene.workspace import Workspace

MARK_HIT_TOLERANCE_M = 0.005
"""A ray's first hit this close to its point on the table sees that point (m): the table's
collision box is its drawn top."""


@dataclass(frozen=True)
class MarksSight:
    """The share (0-1) of each mark's line the point cloud draws at one instant.

    Attributes:
        target_share: Of the target circle's centre line.
        start_share: Of the start cross's two arms.
    """

    target_share: float = 1.0
    start_share: float = 1.0


def target_line_m(ws: Workspace, points: int = 24) -> NDArray[np.float64]:
    """(points, 3) points spread evenly round the target circle's centre line, on the table
    (base frame, m)."""
    a = np.linspace(0.0, 2 * np.pi, points, endpoint=False)
    r = ws.target_circle_radius_m
    x, y = ws.target_xy_m
    return np.column_stack(
        [x + r * np.cos(a), y + r * np.sin(a), np.full(points, ws.table_top_z_m)]
    )


def start_line_m(ws: Workspace, points_per_arm: int = 12) -> NDArray[np.float64]:
    """(2 * points_per_arm, 3) points spread evenly along the start cross's two arms, on the
    table (base frame, m)."""
    # At the middles of equal pieces: a tip drawn is a pixel's edge away from being missed.
    s = ((np.arange(points_per_arm) + 0.5) / points_per_arm - 0.5) * ws.cross_size_m
    x, y = ws.start_xy_m
    z = np.full(points_per_arm, ws.table_top_z_m)
    return np.vstack([np.column_stack([x + s, np.full_like(s, y), z]),
                      np.column_stack([np.full_like(s, x), y + s, z])])  # fmt: skip

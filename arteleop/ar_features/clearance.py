"""How far a label drawn beside a mark keeps from what the operator must see under it.

Labels are drawn facing the viewer beside what they label; the target and the bowl lie
behind or in front of that plane. Both are compared where the camera sees them: each thing's
disc projected, through the camera's centre, onto the plane through an anchor (the gripper, the
ring) square to the camera's axis, in that plane's coordinates (m; x right, y down, relative
to the anchor). A disc seen obliquely is an ellipse no wider than the disc, so the disc is a
safe bound.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

Box = tuple[float, float, float, float]
"""A box in the anchor's plane: x from, x to, y from, y to (m; x right, y down)."""


def discs_in_plane(
    T_base_camera: NDArray[np.float64],
    anchor_m: NDArray[np.float64],
    things: Sequence[tuple[NDArray[np.float64], float]],
) -> list[tuple[NDArray[np.float64], float]]:
    """Each thing ``(centre_m, radius_m)`` (base frame, m) as the camera sees it in the plane
    through ``anchor_m`` square to its axis: its centre relative to the anchor and its radius
    scaled to that depth (m). Things at or behind the camera are left out."""
    R, eye = T_base_camera[:3, :3], T_base_camera[:3, 3]
    anchor = R.T @ (anchor_m - eye)
    seen = []
    for centre_m, radius_m in things:
        c = R.T @ (np.asarray(centre_m, dtype=float) - eye)
        if c[2] <= 1e-6 or anchor[2] <= 1e-6:
            continue
        scale = anchor[2] / c[2]
        seen.append((c[:2] * scale - anchor[:2], radius_m * scale))
    return seen


def pushed_out_m(
    box: Box, discs: Sequence[tuple[NDArray[np.float64], float]], gap_m: float
) -> float:
    """How far to move ``box`` away from the anchor along x (outwards: towards the side it is
    on) so that it keeps ``gap_m`` from every disc level with it (m; 0: it does already). A
    disc above or below the box is cleared as it is."""
    x0, x1, y0, y1 = box
    side = 1.0 if x0 + x1 >= 0.0 else -1.0
    near, far = (x0, x1) if side > 0 else (-x1, -x0)  # outwards from the anchor
    shift = 0.0
    for u, reach in sorted(
        (side * c[0], r + gap_m)
        for c, r in discs
        if abs(c[1] - (y0 + y1) / 2) < r + gap_m + (y1 - y0) / 2
    ):
        if u - reach < far + shift and u + reach > near + shift:
            shift = u + reach - near
    return shift

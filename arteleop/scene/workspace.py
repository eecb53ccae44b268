"""Sizes and poses of everything on the table, in Baxter's base frame (m)."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from arteleop.errors import WorkspaceError
from arteleop.scene.bowl import BowlSpec


@dataclass(frozen=True)
class Box:
    """An axis-aligned box in the base frame: centre and half extents (m), each (3,)."""

    center_m: NDArray[np.float64]
    half_extents_m: NDArray[np.float64]


@dataclass(frozen=True)
class Workspace:
    """The remote workspace. All positions are in Baxter's ``base`` frame, in metres.

    Baxter's base frame sits in the torso, about 0.93 m above the floor on the pedestal; a 0.73 m
    table therefore has its top at z = -0.20 m.

    Attributes:
        table_center_xy_m: Centre of the table top (x forward, y to Baxter's left).
        table_size_m: Table top extent along x (depth) and y (width).
        table_top_z_m: Height of the table top.
        table_thickness_m: Thickness of the table slab.
        table_rgba: Table colour.
        start_xy_m: The start point (cross marker); where the bowl starts unless ``bowl_xy_m``.
        target_xy_m: Where the bowl must go (circle marker).
        bowl_xy_m: Where the bowl starts when not on the start cross (None: on it). A task whose
            object is not the bowl (pointing, which starts over the cross) puts it out of the way.
        bowl: The bowl.
        cross_size_m: Arm length of the start cross, tip to tip.
        marker_line_width_m: Line width of both markers.
        target_circle_radius_m: Radius of the target circle's centre line; slightly larger than
            the bowl's foot so a placed bowl leaves the circle visible around it.
        marker_rgba: Marker colour.
    """

    table_center_xy_m: tuple[float, float] = (0.75, -0.15)
    table_size_m: tuple[float, float] = (0.8, 1.2)
    table_top_z_m: float = -0.20
    table_thickness_m: float = 0.05
    table_rgba: tuple[float, float, float, float] = (0.72, 0.72, 0.70, 1.0)
    start_xy_m: tuple[float, float] = (0.68, -0.45)
    target_xy_m: tuple[float, float] = (0.68, -0.10)
    bowl_xy_m: tuple[float, float] | None = None
    bowl: BowlSpec = field(default_factory=BowlSpec)
    cross_size_m: float = 0.10
    marker_line_width_m: float = 0.012
    target_circle_radius_m: float = 0.06
    marker_rgba: tuple[float, float, float, float] = (0.05, 0.05, 0.05, 1.0)

    def __post_init__(self) -> None:
        if min(self.table_size_m) <= 0 or self.table_thickness_m <= 0:
            raise WorkspaceError(
                f"Table size {self.table_size_m} and thickness {self.table_thickness_m} must be > 0"
            )
        for name in ("start_xy_m", "target_xy_m", "bowl_xy_m"):
            if getattr(self, name) is None and name == "bowl_xy_m":
                continue
            xy = np.asarray(getattr(self, name))
            if xy.shape != (2,) or not np.all(np.isfinite(xy)):
                raise WorkspaceError(
                    f"Workspace.{name}={getattr(self, name)} must be two finite numbers"
                )
            lo, hi = self.table_bounds_xy_m()
            r = self.bowl.rim_radius_m
            if np.any(xy - r < lo) or np.any(xy + r > hi):
                raise WorkspaceError(
                    f"Workspace.{name}={tuple(xy.tolist())}: a bowl of radius {r} m there "
                    f"overhangs the table, which spans x in [{lo[0]:.3f}, {hi[0]:.3f}] and y in "
                    f"[{lo[1]:.3f}, {hi[1]:.3f}] m."
                )
        gap = float(np.linalg.norm(np.subtract(self.bowl_start_xy_m, self.target_xy_m)))
        if gap < self.bowl.diameter_m:
            raise WorkspaceError(
                f"The bowl's start {self.bowl_start_xy_m} and target {self.target_xy_m} are "
                f"{gap:.3f} m apart, less than the bowl's diameter {self.bowl.diameter_m} m: "
                "the task is trivial."
            )

    def table_box(self) -> Box:
        """The table slab as a box in the base frame."""
        half = (self.table_size_m[0] / 2, self.table_size_m[1] / 2, self.table_thickness_m / 2)
        center = (*self.table_center_xy_m, self.table_top_z_m - self.table_thickness_m / 2)
        return Box(np.array(center), np.array(half))

    def table_bounds_xy_m(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """(min corner, max corner) of the table top in x and y."""
        c, s = np.asarray(self.table_center_xy_m), np.asarray(self.table_size_m)
        return c - s / 2, c + s / 2

    def on_table(self, xy_m: tuple[float, float] | NDArray[np.float64]) -> NDArray[np.float64]:
        """The 3D point on the table top below ``xy_m``."""
        return np.array([xy_m[0], xy_m[1], self.table_top_z_m], dtype=np.float64)

    @property
    def start_m(self) -> NDArray[np.float64]:
        """Start point on the table top (x, y, z)."""
        return self.on_table(self.start_xy_m)

    @property
    def bowl_start_xy_m(self) -> tuple[float, float]:
        """Where the bowl starts (x, y): ``bowl_xy_m``, or on the start cross."""
        return self.start_xy_m if self.bowl_xy_m is None else self.bowl_xy_m

    @property
    def target_m(self) -> NDArray[np.float64]:
        """Target point on the table top (x, y, z)."""
        return self.on_table(self.target_xy_m)

    def camera_landmarks_m(self) -> dict[str, NDArray[np.float64]]:
        """What the head camera must see of the task, by name (base frame, m): the start and
        target markers and the bowl's rim where it starts and over the target."""
        rim = np.array([0.0, 0.0, self.bowl.height_m])
        return {
            "start marker": self.start_m,
            "target marker": self.target_m,
            "bowl rim at the start": self.on_table(self.bowl_start_xy_m) + rim,
            "bowl rim at the target": self.target_m + rim,
        }

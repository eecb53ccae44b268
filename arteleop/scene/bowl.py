"""The bowl: a thin-walled, radially symmetric shell built from a revolved profile.

Frame: the bowl's origin is the centre of its bottom face, z along its axis of symmetry.
The outer wall follows ``r(h) = r_bottom + (r_rim - r_bottom) * sin(pi/2 * h / height)``:
it flares from the foot and is vertical at the rim, where a parallel gripper pinches it.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from arteleop.errors import ConfigurationError

GRASP_DEPTH_M = 0.015
"""How far below the rim the tool frame goes to pinch the wall (m)."""


@dataclass(frozen=True)
class BowlSpec:
    """Size and physical properties of the bowl.

    Attributes:
        diameter_m: Outer diameter at the rim (m). docs/explanation/study.md: 16 cm.
        height_m: Height from the bottom face to the rim (m). docs/explanation/study.md: 7 cm.
        bottom_diameter_m: Outer diameter of the foot (m).
        wall_thickness_m: Thickness of wall and floor (m); this is what the gripper pinches.
        mass_kg: Mass (kg); a plastic bowl of this size weighs about 0.1 kg.
        friction: Lateral friction coefficient of its surface.
        rgba: Colour, red-green-blue-alpha in 0..1. A saturated yellow that the camera can tell
            from the red and black robot, the grey table and the black markers.
    """

    diameter_m: float = 0.16
    height_m: float = 0.07
    bottom_diameter_m: float = 0.09
    wall_thickness_m: float = 0.004
    mass_kg: float = 0.1
    friction: float = 1.0
    rgba: tuple[float, float, float, float] = (0.95, 0.8, 0.1, 1.0)

    def __post_init__(self) -> None:
        positive = ("diameter_m", "height_m", "bottom_diameter_m", "wall_thickness_m", "mass_kg")
        for name in positive:
            if not getattr(self, name) > 0:
                raise ConfigurationError(f"BowlSpec.{name} must be > 0, got {getattr(self, name)}")
        if self.bottom_diameter_m > self.diameter_m:
            raise ConfigurationError(
                f"BowlSpec.bottom_diameter_m={self.bottom_diameter_m} exceeds diameter_m="
                f"{self.diameter_m}: a bowl flares upwards."
            )
        if 2 * self.wall_thickness_m >= min(self.bottom_diameter_m, self.height_m):
            raise ConfigurationError(
                f"BowlSpec.wall_thickness_m={self.wall_thickness_m} leaves no cavity in a bowl of "
                f"height {self.height_m} and foot {self.bottom_diameter_m}."
            )

    @cached_property
    def center_of_mass_height_m(self) -> float:
        """Height of the centre of mass above the bottom face (m), from the closed mesh."""
        return _mesh_center_of_mass(*bowl_mesh(self))[2]

    @property
    def rim_radius_m(self) -> float:
        return self.diameter_m / 2

    @property
    def bottom_radius_m(self) -> float:
        return self.bottom_diameter_m / 2

    def grasp_offset_m(self, direction_xy: tuple[float, float] = (0.0, 1.0)) -> NDArray[np.float64]:
        """Grasp point in the bowl's frame (m): the middle of the wall, ``GRASP_DEPTH_M`` below
        the rim, on the side ``direction_xy`` points to (+y by default, where the open fingers,
        which open along the base's y, straddle the wall)."""
        d = np.asarray(direction_xy, dtype=np.float64)
        d = d / np.linalg.norm(d)
        r = self.rim_radius_m - self.wall_thickness_m / 2
        return np.array([r * d[0], r * d[1], self.height_m - GRASP_DEPTH_M])

    def outer_radius_m(self, h_m: NDArray[np.float64] | float) -> NDArray[np.float64]:
        """Outer radius (m) at height ``h_m`` above the bottom face."""
        h = np.clip(np.asarray(h_m, dtype=np.float64), 0.0, self.height_m)
        span = self.rim_radius_m - self.bottom_radius_m
        return self.bottom_radius_m + span * np.sin(0.5 * np.pi * h / self.height_m)

    def lowest_z_m(self, T_base_bowl: NDArray[np.float64]) -> float:
        """Height (m, base frame) of the lowest point of the outer wall with the bowl at
        ``T_base_bowl``: its bottom face's centre when upright, its foot's edge when tilted.

        Each circle of the wall, radius ``r(h)`` at height ``h`` on the axis ``a``, reaches
        ``h a_z - r(h) sqrt(1 - a_z^2)`` below the origin; the lowest of 64 circles is taken.
        """
        a_z = float(T_base_bowl[2, 2])
        h, r = self._wall_circles
        reach = h * a_z - r * np.sqrt(max(0.0, 1.0 - a_z * a_z))
        return float(T_base_bowl[2, 3] + reach.min())

    @cached_property
    def _wall_circles(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """64 heights up the outer wall and their radii (m): built once, read every tick."""
        h = np.linspace(0.0, self.height_m, 64)
        return h, self.outer_radius_m(h)

    def profile(self, n: int = 16) -> NDArray[np.float64]:
        """Closed wall cross-section as (r, h) points, shape (2n + 2, 2), counter-clockwise.

        Runs up the outer wall, across the rim, down the inner wall and back along the axis.
        """
        t = self.wall_thickness_m
        h_out = np.linspace(0.0, self.height_m, n)
        outer = np.column_stack([self.outer_radius_m(h_out), h_out])
        h_in = np.linspace(self.height_m, t, n)
        inner = np.column_stack([self.outer_radius_m(h_in) - t, h_in])
        axis = np.array([[0.0, t], [0.0, 0.0]])
        return np.vstack([outer, inner, axis])


def bowl_mesh(
    spec: BowlSpec, segments: int = 48, rings: int = 16
) -> tuple[NDArray[np.float64], NDArray[np.int32]]:
    """Closed triangle mesh of the bowl in its own frame: (vertices (N, 3) m, triangles (M, 3)).

    The mesh is watertight and its triangles wind counter-clockwise seen from outside.
    """
    prof = spec.profile(rings)
    # Drop the axis points: both lie on r = 0 and become the two poles of the revolved surface.
    ring_prof, poles = prof[:-2], prof[-2:]
    angles = np.linspace(0.0, 2 * np.pi, segments, endpoint=False)
    c, s = np.cos(angles), np.sin(angles)
    k = len(ring_prof)
    verts = np.column_stack(
        [
            np.outer(ring_prof[:, 0], c).ravel(),
            np.outer(ring_prof[:, 0], s).ravel(),
            np.repeat(ring_prof[:, 1], segments),
        ]
    )
    inner_pole, bottom_pole = len(verts), len(verts) + 1
    verts = np.vstack([verts, [[0.0, 0.0, poles[0, 1]], [0.0, 0.0, poles[1, 1]]]])

    i = np.arange(k - 1)[:, None] * segments
    j = np.arange(segments)[None, :]
    jn = (j + 1) % segments
    a, b, cc, d = i + j, i + jn, i + segments + j, i + segments + jn
    quads = np.stack([np.stack([a, b, d], -1), np.stack([a, d, cc], -1)], axis=2).reshape(-1, 3)
    jj = np.arange(segments)
    last = (k - 1) * segments
    floor = np.column_stack([np.full(segments, inner_pole), last + jj, last + (jj + 1) % segments])
    bottom = np.column_stack([np.full(segments, bottom_pole), (jj + 1) % segments, jj])
    return verts, np.vstack([quads, floor, bottom]).astype(np.int32)


def _mesh_center_of_mass(
    verts: NDArray[np.float64], tris: NDArray[np.int32]
) -> NDArray[np.float64]:
    # Signed tetrahedra against the origin: exact for a closed, consistently wound mesh.
    a, b, c = verts[tris[:, 0]], verts[tris[:, 1]], verts[tris[:, 2]]
    vol = np.einsum("ij,ij->i", a, np.cross(b, c)) / 6.0
    return (vol[:, None] * (a + b + c) / 4.0).sum(axis=0) / vol.sum()


@dataclass(frozen=True)
class CollisionBox:
    """One convex piece of the bowl's compound collision shape, in the bowl frame."""

    half_extents_m: tuple[float, float, float]
    position_m: tuple[float, float, float]
    quat_wxyz: tuple[float, float, float, float]


def bowl_collision_boxes(spec: BowlSpec, segments: int = 20, rings: int = 4) -> list[CollisionBox]:
    """Thin boxes that tile the wall, plus one flat box for the floor.

    A convex hull would fill the bowl and leave nothing to pinch; tiling the wall with boxes
    of the wall's thickness lets the fingers close on either face of it.
    """
    t = spec.wall_thickness_m
    h = np.linspace(t, spec.height_m, rings + 1)
    r_mid = spec.outer_radius_m(h) - t / 2
    boxes: list[CollisionBox] = []
    for k in range(rings):
        dr, dh = r_mid[k + 1] - r_mid[k], h[k + 1] - h[k]
        length = float(np.hypot(dr, dh))
        tilt = float(np.arctan2(dr, dh))  # lean of the wall away from vertical (rad)
        rc, hc = 0.5 * (r_mid[k] + r_mid[k + 1]), 0.5 * (h[k] + h[k + 1])
        half_width = rc * np.pi / segments * 1.15  # overlap neighbours so no finger slips between
        for m in range(segments):
            yaw = 2 * np.pi * m / segments
            # Box frame: x radial (tilted with the wall), y tangential, z along the wall.
            qyaw = np.array([np.cos(yaw / 2), 0, 0, np.sin(yaw / 2)])
            qtilt = np.array([np.cos(tilt / 2), 0, np.sin(tilt / 2), 0])
            q = _quat_mul(qyaw, qtilt)
            boxes.append(
                CollisionBox(
                    half_extents_m=(t / 2, float(half_width), length / 2 * 1.02),
                    position_m=(float(rc * np.cos(yaw)), float(rc * np.sin(yaw)), float(hc)),
                    quat_wxyz=tuple(float(v) for v in q),  # type: ignore[arg-type]
                )
            )
    half_floor = spec.bottom_radius_m / np.sqrt(2) + t
    boxes.append(
        CollisionBox((half_floor, half_floor, t / 2), (0.0, 0.0, t / 2), (1.0, 0.0, 0.0, 0.0))
    )
    return boxes


def _quat_mul(a: NDArray[np.float64], b: NDArray[np.float64]) -> NDArray[np.float64]:
    w1, x1, y1, z1 = a
    w2, x2, y2, z2 = b
    return np.array(
        [
            w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2,
            w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
            w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
            w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2,
        ]
    )

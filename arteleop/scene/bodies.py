"""PyBullet bodies of the workspace: table, bowl and markers. World frame = Baxter's base."""

from __future__ import annotations

import itertools
import tempfile
from pathlib import Path

import numpy as np
import pybullet as p
from numpy.typing import NDArray
from pybullet_utils.bullet_client import BulletClient

from arteleop.scene.bowl import CollisionBox, bowl_collision_boxes, bowl_mesh
from arteleop.scene.workspace import Workspace
from arteleop.transforms import pose_to_transform, transform_points

_MARKER_LIFT_M = 0.0005  # markers float just above the table top so they never z-fight with it


def add_table(client: BulletClient, ws: Workspace) -> int:
    """Static table slab whose top face is at ``ws.table_top_z_m``."""
    box = ws.table_box()
    half, center = box.half_extents_m.tolist(), box.center_m.tolist()
    col = client.createCollisionShape(p.GEOM_BOX, halfExtents=half)
    vis = client.createVisualShape(p.GEOM_BOX, halfExtents=half, rgbaColor=ws.table_rgba)
    body = client.createMultiBody(0.0, col, vis, basePosition=center)
    client.changeDynamics(body, -1, lateralFriction=0.8)
    return body


def add_bowl(client: BulletClient, ws: Workspace, xy_m: tuple[float, float]) -> int:
    """Dynamic bowl standing upright on the table at ``xy_m``; it sleeps while at rest."""
    spec = ws.bowl
    # createCollisionShapeArray keeps only its first 16 children, too few to tile the wall. An
    # OBJ with one object per box loads as a compound with one convex hull each, without a cap.
    with tempfile.TemporaryDirectory() as tmp:
        obj = Path(tmp) / "bowl_collision.obj"
        obj.write_text(_boxes_to_obj(bowl_collision_boxes(spec)))
        col = client.createCollisionShape(p.GEOM_MESH, fileName=str(obj))
    verts, tris = bowl_mesh(spec)
    vis = client.createVisualShape(
        p.GEOM_MESH, vertices=verts.tolist(), indices=tris.ravel().tolist(), rgbaColor=spec.rgba
    )
    body = client.createMultiBody(
        spec.mass_kg,
        col,
        vis,
        basePosition=[xy_m[0], xy_m[1], ws.table_top_z_m],
        baseInertialFramePosition=[0.0, 0.0, spec.center_of_mass_height_m],
    )
    client.changeDynamics(
        body,
        -1,
        lateralFriction=spec.friction,
        rollingFriction=1e-4,
        activationState=p.ACTIVATION_STATE_ENABLE_SLEEPING,
    )
    return body


def _boxes_to_obj(boxes: list[CollisionBox]) -> str:
    corners = np.array(list(itertools.product((-1.0, 1.0), repeat=3)))  # bit order x, y, z
    faces = ((0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3))
    lines = []
    for k, box in enumerate(boxes):
        T = pose_to_transform(box.position_m, box.quat_wxyz)
        lines.append(f"o box{k}")
        lines += [
            f"v {x:.7f} {y:.7f} {z:.7f}"
            for x, y, z in transform_points(T, corners * box.half_extents_m)
        ]
        lines += ["f " + " ".join(str(8 * k + i + 1) for i in face) for face in faces]
    return "\n".join(lines) + "\n"


def add_start_cross(client: BulletClient, ws: Workspace) -> int:
    """Visual-only cross marker centred on the start point."""
    half = [ws.cross_size_m / 2, ws.marker_line_width_m / 2, 0.0002]
    vis = client.createVisualShapeArray(
        shapeTypes=[p.GEOM_BOX, p.GEOM_BOX],
        halfExtents=[half, [half[1], half[0], half[2]]],
        rgbaColors=[ws.marker_rgba, ws.marker_rgba],
        visualFramePositions=[[0, 0, 0], [0, 0, 0]],
    )
    z = ws.table_top_z_m + _MARKER_LIFT_M
    return client.createMultiBody(0.0, -1, vis, basePosition=[*ws.start_xy_m, z])


def target_ring_mesh(
    ws: Workspace, segments: int = 64
) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """The target marker's ring in its own frame (centred, on z = 0): (vertices (N, 3) m,
    triangles (M, 3))."""
    r0 = ws.target_circle_radius_m - ws.marker_line_width_m / 2
    r1 = ws.target_circle_radius_m + ws.marker_line_width_m / 2
    a = np.linspace(0, 2 * np.pi, segments, endpoint=False)
    ring = np.vstack(
        [np.column_stack([r * np.cos(a), r * np.sin(a), np.zeros(segments)]) for r in (r0, r1)]
    )
    j = np.arange(segments)
    k = (j + 1) % segments
    tris = np.vstack(
        [np.column_stack([j, segments + k, k]), np.column_stack([j, segments + j, segments + k])]
    )
    return ring, tris


def add_target_circle(client: BulletClient, ws: Workspace) -> int:
    """Visual-only ring marker centred on the target point."""
    ring, tris = target_ring_mesh(ws)
    vis = client.createVisualShape(
        p.GEOM_MESH, vertices=ring.tolist(), indices=tris.ravel().tolist(), rgbaColor=ws.marker_rgba
    )
    z = ws.table_top_z_m + _MARKER_LIFT_M
    return client.createMultiBody(0.0, -1, vis, basePosition=[*ws.target_xy_m, z])

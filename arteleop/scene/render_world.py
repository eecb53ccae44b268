"""A second PyBullet world that is only drawn, never stepped: what the head camera sees.

The physics world loads Baxter with its fixed links merged, which makes a step several times
cheaper, but PyBullet's merge drops some visual shapes (the white rings of the arm) and mixes up
the colours of others. The camera therefore renders this copy of the scene: Baxter unmerged
from the same URDF, the same table, markers and bowl, with the moving state (the right arm's
joints and the bowl's pose) copied over from the physics world before each frame.

It draws with OpenGL (:class:`~arteleop.scene.gl_renderer.GLScene`, the world's own shapes
and poses) or with PyBullet's TinyRenderer. With TinyRenderer and the joints that move given,
it draws in two layers: the head camera never moves, so what never moves (the table, the
markers, the robot but for the links those joints carry) is drawn once per camera pose and
kept, and each frame draws only what moves (those links and the bowl) and takes each pixel from
the nearer layer. TinyRenderer shades each surface by itself (no shadows here), so the two
layers give the image of a full render (a test compares them).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pybullet as p
from pybullet_utils.bullet_client import BulletClient

from arteleop.errors import SimulationError
from arteleop.robot.description import hide_links
from arteleop.robot.native_output import native_stdout_silenced
from arteleop.scene.bodies import (
    add_bowl,
    add_start_cross,
    add_table,
    add_target_circle,
    target_ring_mesh,
)
from arteleop.scene.bowl import bowl_mesh
from arteleop.scene.camera import RawImage, RenderRequest, render
from arteleop.scene.workspace import Workspace


@dataclass(frozen=True)
class SceneState:
    """What moves in the scene, in the base frame: joint positions (rad or m, by joint name) and
    the bowl's centre-of-mass pose (PyBullet's x, y, z, w quaternion)."""

    joint_positions: dict[str, float]
    bowl_com_position_m: tuple[float, float, float]
    bowl_com_quat_xyzw: tuple[float, float, float, float]


class RenderWorld:
    """The drawn copy of the site; bodies are added in the physics world's order, so body ids
    (and segmentation masks) mean the same in both. ``renderer`` is ``"gl"`` or ``"tiny"``
    (:func:`~arteleop.scene.gl_renderer.resolve_renderer` turns ``"auto"`` into one)."""

    def __init__(
        self,
        robot_urdf: Path,
        ws: Workspace,
        body_ids: Sequence[int],
        moving_joints: Sequence[str] = (),
        renderer: str = "tiny",
    ) -> None:
        with native_stdout_silenced():
            self.client = BulletClient(connection_mode=p.DIRECT)
            robot = self.client.loadURDF(str(robot_urdf), useFixedBase=True)
        ids = [
            robot,
            add_table(self.client, ws),
            add_start_cross(self.client, ws),
            add_target_circle(self.client, ws),
            add_bowl(self.client, ws, ws.bowl_start_xy_m),
        ]
        if ids != list(body_ids):
            self.client.disconnect()
            raise SimulationError(
                f"render world body ids {ids} differ from the physics world's {body_ids}"
            )
        self.body_ids = tuple(ids)
        self._robot, self._bowl = robot, ids[-1]
        self._joint_index = {
            self.client.getJointInfo(robot, i)[1].decode(): i
            for i in range(self.client.getNumJoints(robot))
        }

        self.renderer = renderer
        self._layers = None
        self._gl = None
        try:
            if renderer == "gl":
                from arteleop.scene.gl_renderer import GLScene

                target, bowl = ids[3], ids[4]
                meshes = {target: target_ring_mesh(ws), bowl: bowl_mesh(ws.bowl)}
                self._gl = GLScene(self.client, self.body_ids, meshes)
            elif moving_joints:
                self._layers = _Layers(self.client, robot, robot_urdf, ws, moving_joints)
        except BaseException:
            self.client.disconnect()
            raise

    def sync(self, state: SceneState) -> None:
        """Copy the moving state over from the physics world."""
        _sync(self.client, self._robot, self._bowl, self._joint_index, state)
        if self._layers is not None:
            self._layers.sync(state, self._joint_index)

    def render(self, request: RenderRequest) -> RawImage:
        """Render ``request`` of the synced state. A world holding a body another module added
        (e.g. a calibration marker, printed with a texture) is drawn fully by TinyRenderer;
        otherwise with OpenGL, or in TinyRenderer's two layers when the world has them (fully
        when segmentation is asked for). The full-size image is drawn, then thinned as the
        request says."""
        return self._render_full(request).thinned(request.stride)

    def _render_full(self, request: RenderRequest) -> RawImage:
        if self.client.getNumBodies() != len(self.body_ids):
            return render(self.client, request)
        if self._gl is not None:
            return self._gl.render(request)
        if self._layers is None or request.with_segmentation:
            return render(self.client, request)
        return self._layers.render(request)

    def close(self) -> None:
        if self._gl is not None:
            self._gl.close()
        if self._layers is not None:
            self._layers.close()
        if self.client.isConnected():
            self.client.disconnect()


class _Layers:
    """The scene in two worlds: one holds what never moves, drawn once per camera pose and
    static joint state, the other what moves, drawn every frame."""

    def __init__(
        self,
        full: BulletClient,
        robot: int,
        robot_urdf: Path,
        ws: Workspace,
        moving_joints: Sequence[str],
    ) -> None:
        joints = [full.getJointInfo(robot, i) for i in range(full.getNumJoints(robot))]
        unknown = set(moving_joints) - {j[1].decode() for j in joints}
        if unknown:
            raise SimulationError(f"moving joints {sorted(unknown)} are not in {robot_urdf}")
        # PyBullet lists a link after its parent, so one pass finds every link the joints carry.
        moving: set[int] = set()
        for i, info in enumerate(joints):
            if info[1].decode() in moving_joints or info[16] in moving:
                moving.add(i)
        moving_links = {joints[i][12].decode() for i in moving}
        still_links = {j[12].decode() for j in joints} - moving_links
        still_links.add(full.getBodyInfo(robot)[0].decode())  # the root link
        self._still_joints = {joints[i][1].decode() for i in range(len(joints)) if i not in moving}
        with native_stdout_silenced():
            self.still = BulletClient(connection_mode=p.DIRECT)
            self.moving = BulletClient(connection_mode=p.DIRECT)
            self._still_robot = self.still.loadURDF(
                str(hide_links(robot_urdf, moving_links)), useFixedBase=True
            )
            self._moving_robot = self.moving.loadURDF(
                str(hide_links(robot_urdf, still_links)), useFixedBase=True
            )
        add_table(self.still, ws)
        add_start_cross(self.still, ws)
        add_target_circle(self.still, ws)
        self._moving_bowl = add_bowl(self.moving, ws, ws.bowl_start_xy_m)
        self._still_state: dict[str, float] = {}
        self._still_images: dict[tuple[object, ...], RawImage] = {}

    def sync(self, state: SceneState, joint_index: dict[str, int]) -> None:
        _sync(self.moving, self._moving_robot, self._moving_bowl, joint_index, state)
        still = {n: q for n, q in state.joint_positions.items() if n in self._still_joints}
        if any(self._still_state.get(n) != q for n, q in still.items()):
            for name, q in still.items():
                self.still.resetJointState(self._still_robot, joint_index[name], q)
            self._still_state.update(still)
            self._still_images.clear()

    def render(self, request: RenderRequest) -> RawImage:
        key = (request.width_px, request.height_px, tuple(request.view_gl),
               tuple(request.projection_gl))  # fmt: skip
        still = self._still_images.get(key)
        if still is None:
            still = self._still_images[key] = render(self.still, request)
        moving = render(self.moving, request)
        # A pixel's four bytes as one uint32: one select per pixel instead of four.
        rgba = np.where(
            moving.zbuf < still.zbuf,
            moving.rgba.view(np.uint32)[..., 0],
            still.rgba.view(np.uint32)[..., 0],
        )
        return RawImage(rgba[..., None].view(np.uint8), np.minimum(moving.zbuf, still.zbuf), None)

    def close(self) -> None:
        for client in (self.still, self.moving):
            if client.isConnected():
                client.disconnect()


def _sync(
    client: BulletClient, robot: int, bowl: int, joint_index: dict[str, int], state: SceneState
) -> None:
    for name, q in state.joint_positions.items():
        client.resetJointState(robot, joint_index[name], q)
    client.resetBasePositionAndOrientation(
        bowl, state.bowl_com_position_m, state.bowl_com_quat_xyzw
    )

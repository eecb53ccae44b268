"""A second PyBullet world that is only drawn, never stepped: what the head camera sees.

The physics world loads Baxter with its fixed links merged, which makes a step several times
cheaper, but PyBullet's merge drops some visual shapes (the white rings of the arm) and mixes up
the colours of others. The camera therefore renders this copy of the scene: Baxter unmerged
from the same URDF, the same table, markers and bowl, with the moving state (the right arm's
joints and the bowl's pose) copied over from the physics world before each frame.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import pybullet as p
from pybullet_utils.bullet_client import BulletClient

from arteleop.errors import SimulationError
from arteleop.robot.native_output import native_stdout_silenced
from arteleop.scene.bodies import add_bowl, add_start_cross, add_table, add_target_circle
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
    (and segmentation masks) mean the same in both."""

    def __init__(self, robot_urdf: Path, ws: Workspace, body_ids: Sequence[int]) -> None:
        with native_stdout_silenced():
            self.client = BulletClient(connection_mode=p.DIRECT)
            robot = self.client.loadURDF(str(robot_urdf), useFixedBase=True)
        ids = [
            robot,
            add_table(self.client, ws),
            add_start_cross(self.client, ws),
            add_target_circle(self.client, ws),
            add_bowl(self.client, ws, ws.start_xy_m),
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

    def sync(self, state: SceneState) -> None:
        """Copy the moving state over from the physics world."""
        for name, q in state.joint_positions.items():
            self.client.resetJointState(self._robot, self._joint_index[name], q)
        self.client.resetBasePositionAndOrientation(
            self._bowl, state.bowl_com_position_m, state.bowl_com_quat_xyzw
        )

    def close(self) -> None:
        if self.client.isConnected():
            self.client.disconnect()

"""Embodiment cue: a 1:1 translucent model of the robot, animated by its joint encoders.

It shows the arm where the camera cannot: out of the image, or nearer than the sensor's
minimum range. Built from the same URDF and render meshes as the head camera's scene.
"""

from __future__ import annotations

import numpy as np
import viser
from viser.extras import ViserUrdf

from arteleop.ar_features.assets import ViewAssets
from arteleop.ar_features.display_frame import DisplayFrame
from arteleop.ar_features.layer import Layer
from arteleop.ar_features.layers.colors import GHOST_RGBA

GHOST_NODE = "/ar/ghost"


class GhostLayer(Layer):
    """The robot model; its base frame is the scene's world frame (Baxter's base)."""

    cue = "ghost"

    def __init__(self, server: viser.ViserServer, assets: ViewAssets) -> None:
        super().__init__()
        self._assets = assets
        self._root = server.scene.add_frame(GHOST_NODE, show_axes=False, visible=False)
        self._urdf = ViserUrdf(
            server, assets.robot_urdf, root_node_name=GHOST_NODE, mesh_color_override=GHOST_RGBA
        )
        self._names = self._urdf.get_actuated_joint_names()

    def update(self, frame: DisplayFrame) -> None:
        q = self._assets.joint_positions(frame.arm_q_rad, frame.gripper_closure)
        self._urdf.update_cfg(np.array([q.get(name, 0.0) for name in self._names]))

    def _set_visible(self, visible: bool) -> None:
        self._root.visible = visible

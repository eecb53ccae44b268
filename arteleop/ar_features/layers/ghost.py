"""Ghosts: 1:1 translucent models of the robot, built from the same URDF and render meshes as
the head camera's scene.

The embodiment cue is animated by the joint encoders: it shows the arm where the camera cannot
(out of the image, or nearer than the sensor's minimum range). The predictive ghost shows the
arm where the commands already sent will put it, ahead of a delayed view.
"""

from __future__ import annotations

import numpy as np
import viser
import yourdfpy
from numpy.typing import NDArray
from scipy.spatial.transform import Rotation
from viser.extras import ViserUrdf

from arteleop.ar_features.assets import ViewAssets
from arteleop.ar_features.display_frame import DisplayFrame
from arteleop.ar_features.layer import Layer
from arteleop.ar_features.layers.colors import GHOST_RGBA, PREDICTIVE_RGBA
from arteleop.transforms import make_transform, transform_to_pose

GHOST_NODE = "/ar/ghost"
PREDICTIVE_NODE = "/ar/predictive_ghost"


class GhostLayer(Layer):
    """The robot model at the frame's encoder readings; its base frame is the scene's world
    frame (Baxter's base).

    The first update poses every joint through viser's ``ViserUrdf.update_cfg``; later ones
    pose only the joints that move (the right arm and its fingers) from each joint's origin and
    axis. ``update_cfg`` re-poses all 56 joint frames in Python, 14 ms a frame, most of the
    view's cost; the others never move.
    """

    cue = "ghost"
    node = GHOST_NODE
    rgba = GHOST_RGBA

    def __init__(self, server: viser.ViserServer, assets: ViewAssets) -> None:
        super().__init__()
        self._assets = assets
        self._root = server.scene.add_frame(self.node, show_axes=False, visible=False)
        self._urdf = ViserUrdf(
            server, assets.robot_urdf, root_node_name=self.node, mesh_color_override=self.rgba
        )
        self._names = self._urdf.get_actuated_joint_names()
        moving = {*assets.arm_joints, *assets.finger_joints}
        # ViserUrdf keeps its joints' frames in private lists (viser is pinned in pyproject).
        self._moving = [
            (handle, joint)
            for joint, handle in zip(
                self._urdf._joint_map_values, self._urdf._joint_frames, strict=True
            )
            if joint.name in moving
        ]
        self._posed = False

    def arm(self, frame: DisplayFrame) -> tuple[NDArray[np.float64], float]:
        """The arm's joints (rad) and the gripper's closure that the ghost shows."""
        return frame.arm_q_rad, frame.gripper_closure

    def update(self, frame: DisplayFrame) -> None:
        q = self._assets.joint_positions(*self.arm(frame))
        if not self._posed:
            self._urdf.update_cfg(np.array([q.get(name, 0.0) for name in self._names]))
            self._posed = True
            return
        for handle, joint in self._moving:
            position, wxyz = transform_to_pose(_joint_transform(joint, q[joint.name]))
            handle.wxyz = wxyz
            handle.position = position

    def _set_visible(self, visible: bool) -> None:
        self._root.visible = visible


class PredictiveGhostLayer(GhostLayer):
    """The robot model where the commands already sent will put it (:class:`PredictedArm`),
    in its own colour; the frame's own arm where nothing is predicted (no delay to lead)."""

    cue = "predictive_ghost"
    node = PREDICTIVE_NODE
    rgba = PREDICTIVE_RGBA

    def __init__(self, server: viser.ViserServer, assets: ViewAssets) -> None:
        super().__init__(server, assets)
        # Only the arm is predicted: the rest of the robot, drawn around the egocentric
        # camera, would tint the whole view and hide the delayed arm behind it.
        shoulder = self._urdf._urdf.joint_map[assets.arm_joints[0]].child
        for mesh in self._urdf._meshes:
            mesh.visible = f"/{shoulder}/" in mesh.name

    def arm(self, frame: DisplayFrame) -> tuple[NDArray[np.float64], float]:
        if frame.predicted is None:
            return super().arm(frame)
        return frame.predicted.arm_q_rad, frame.predicted.gripper_closure


def _joint_transform(joint: yourdfpy.Joint, q: float) -> NDArray[np.float64]:
    """``T_parent_child`` of a revolute or prismatic URDF joint at position ``q`` (rad or m)."""
    origin = np.eye(4) if joint.origin is None else joint.origin
    axis = np.asarray(joint.axis, dtype=np.float64)
    if joint.type == "prismatic":
        motion = make_transform(np.eye(3), axis * q)
    else:
        motion = make_transform(Rotation.from_rotvec(axis * q).as_matrix(), np.zeros(3))
    return origin @ motion

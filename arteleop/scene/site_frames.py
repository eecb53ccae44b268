"""The remote system's frames in one :class:`TransformGraph`: what places the point cloud, the
tracked bowl and every AR layer.

Frames:
- the robot's links, ``base`` at the root, the arm's edges set from its encoders;
- ``head_camera``, the camera's optical frame, joined to ``base`` by a ``calibration`` edge:
  the camera's registration (``HeadCamera.registered``, e.g. from ``arteleop calibrate``),
  never the simulator's true pose, which is used only to measure errors;
- ``table`` (the centre of the table top), ``start_marker`` and ``target_marker``: ``fixed``;
- ``bowl``: a ``dynamic`` edge from ``head_camera``, where the camera last saw the bowl's frame
  (from its first sighting on), so the bowl reaches the base frame through the registration,
  as the cloud does.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
from numpy.typing import ArrayLike, NDArray

from arteleop.frames.robot_frames import RobotFrames
from arteleop.frames.transform_graph import EdgeKind, TransformGraph
from arteleop.frames.uncertain_transform import UncertainTransform
from arteleop.robot import BaxterKinematics
from arteleop.scene.workspace import Workspace
from arteleop.transforms import make_transform

BASE_FRAME = "base"
CAMERA_FRAME = "head_camera"
BOWL_FRAME = "bowl"
TABLE_FRAME = "table"
START_MARKER_FRAME = "start_marker"
TARGET_MARKER_FRAME = "target_marker"


class SiteFrames:
    """The site's transform graph (see the module docstring).

    Args:
        kinematics: The robot's model, for its links.
        workspace: Where the table and the markers are.
        T_base_camera: The camera's registered pose (4x4, m), with a covariance if it has one.
        positions: Joint positions (rad or m) of the joints the graph does not follow, e.g.
            the left arm's rest pose; joints not named sit at 0 until :meth:`set_joints`.
    """

    def __init__(
        self,
        kinematics: BaxterKinematics,
        workspace: Workspace,
        T_base_camera: ArrayLike | UncertainTransform,
        positions: Mapping[str, float] | None = None,
    ) -> None:
        self.graph = TransformGraph()
        self._robot = RobotFrames(kinematics)
        self._robot.attach(self.graph, positions)
        self.graph.set(BASE_FRAME, CAMERA_FRAME, T_base_camera, EdgeKind.CALIBRATION)
        places = {
            TABLE_FRAME: workspace.on_table(workspace.table_center_xy_m),
            START_MARKER_FRAME: workspace.start_m,
            TARGET_MARKER_FRAME: workspace.target_m,
        }
        for name, position in places.items():
            self.graph.set(BASE_FRAME, name, make_transform(np.eye(3), position), EdgeKind.FIXED)

    def set_joints(self, positions: Mapping[str, float]) -> None:
        """The named joints' positions (joint name -> rad or m), as the encoders read them."""
        self._robot.update(self.graph, positions)

    def set_bowl_seen(self, T_camera_bowl: NDArray[np.float64]) -> None:
        """Where the camera sees the bowl's frame (4x4 in its optical frame, m)."""
        self.graph.set(CAMERA_FRAME, BOWL_FRAME, T_camera_bowl, EdgeKind.DYNAMIC)

    def T(self, a: str, b: str) -> NDArray[np.float64]:
        """``T_a_b`` (4x4, m)."""
        return self.graph.T(a, b)

    @property
    def T_base_camera(self) -> NDArray[np.float64]:
        """The camera's registered pose in the base frame (4x4, m)."""
        return self.graph.T(BASE_FRAME, CAMERA_FRAME)

"""A robot's links as frames of a :class:`TransformGraph`, from its URDF through pinocchio."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

import pinocchio as pin

from arteleop.errors import ConfigurationError
from arteleop.scene.transform_graph import EdgeKind, TransformGraph


class RobotFrames:
    """Every link of a URDF as a frame, joined to its parent link by the joint between them:
    a ``fixed`` edge for a fixed joint, a ``dynamic`` one for a moving joint, whose transform
    :meth:`update` sets from joint positions (rad or m, by joint name)."""

    def __init__(self, urdf_path: Path) -> None:
        self.model = pin.buildModelFromUrdf(str(urdf_path))
        self._data = self.model.createData()
        frames = self.model.frames
        # (parent link, child link, moving) per joint: a link's frame hangs off the frame of the
        # joint that carries it, which hangs off the parent link's frame.
        self.links: list[tuple[str, str, bool]] = []
        self._ids: list[tuple[int, int]] = []
        for i, frame in enumerate(frames):
            if frame.type != pin.FrameType.BODY or frame.parentFrame == i:
                continue
            joint = frames[frame.parentFrame]
            if joint.type not in (pin.FrameType.JOINT, pin.FrameType.FIXED_JOINT):
                continue
            parent = joint.parentFrame
            if frames[parent].type != pin.FrameType.BODY:
                continue  # the root link: nothing above it in the URDF
            moving = joint.type == pin.FrameType.JOINT
            self.links.append((frames[parent].name, frame.name, moving))
            self._ids.append((parent, i))
        self._q_index = {
            name: self.model.joints[self.model.getJointId(name)].idx_q
            for name in self.model.names[1:]
        }

    def attach(self, graph: TransformGraph, positions: Mapping[str, float] | None = None) -> None:
        """Add every link to ``graph``, the moving joints at ``positions`` (0 if not named)."""
        self._write(graph, positions or {}, everything=True)

    def update(self, graph: TransformGraph, positions: Mapping[str, float]) -> None:
        """Set the moving joints' edges to ``positions`` (joint name -> rad or m)."""
        self._write(graph, positions, everything=False)

    def _write(
        self, graph: TransformGraph, positions: Mapping[str, float], everything: bool
    ) -> None:
        q = pin.neutral(self.model)
        for name, value in positions.items():
            if name not in self._q_index:
                raise ConfigurationError(
                    f"unknown joint '{name}'; the robot's moving joints: {list(self._q_index)}"
                )
            q[self._q_index[name]] = value
        pin.framesForwardKinematics(self.model, self._data, q)
        oMf = self._data.oMf
        for (parent, child, moving), (i, j) in zip(self.links, self._ids, strict=True):
            if moving or everything:
                T = (oMf[i].inverse() * oMf[j]).homogeneous
                graph.set(parent, child, T, EdgeKind.DYNAMIC if moving else EdgeKind.FIXED)

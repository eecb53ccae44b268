"""A robot's links as frames of a :class:`TransformGraph`, from its pinocchio model."""

from __future__ import annotations

from collections.abc import Mapping

import pinocchio as pin

from arteleop.frames.transform_graph import EdgeKind, TransformGraph
from arteleop.frames.uncertain_transform import UncertainTransform
from arteleop.robot import BaxterKinematics


class RobotFrames:
    """Every link of a URDF as a frame, joined to its parent link by the joint between them:
    a ``fixed`` edge for a fixed joint, a ``dynamic`` one for a moving joint, whose transform
    :meth:`update` sets from joint positions (rad or m, by joint name)."""

    def __init__(self, kinematics: BaxterKinematics) -> None:
        self._kinematics = kinematics
        self.model = kinematics.model
        self._data = self.model.createData()
        frames = self.model.frames
        # (parent link, child link, moving) per joint: a link's frame hangs off the frame of the
        # joint that carries it, which hangs off the parent link's frame.
        self.links: list[tuple[str, str, bool]] = []
        self._ids: list[tuple[int, int]] = []
        self._moving: dict[str, tuple[str, str, int, int]] = {}  # joint -> its edge, frame ids
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
            if moving:
                self._moving[joint.name] = (frames[parent].name, frame.name, parent, i)

    def attach(self, graph: TransformGraph, positions: Mapping[str, float] | None = None) -> None:
        """Add every link to ``graph``, the moving joints at ``positions`` (0 if not named)."""
        oMf = self._placements(positions or {})
        for (parent, child, moving), (i, j) in zip(self.links, self._ids, strict=True):
            T = UncertainTransform._trusted((oMf[i].inverse() * oMf[j]).homogeneous)
            graph.set(parent, child, T, EdgeKind.DYNAMIC if moving else EdgeKind.FIXED)

    def update(self, graph: TransformGraph, positions: Mapping[str, float]) -> None:
        """Set the edges of the joints named in ``positions`` (joint name -> rad or m); the
        other joints keep theirs."""
        oMf = self._placements(positions)
        # A joint's edge depends on its own position only, so the joints not named (at 0 in
        # the configuration) do not spoil the edges of those that are.
        for name in positions:
            edge = self._moving.get(name)
            if edge is not None:
                parent, child, i, j = edge
                # Rigid by construction: the graph's checks would cost more than the kinematics.
                T = UncertainTransform._trusted((oMf[i].inverse() * oMf[j]).homogeneous)
                graph.set(parent, child, T, EdgeKind.DYNAMIC)

    def _placements(self, positions: Mapping[str, float]) -> pin.StdVec_SE3:
        pin.framesForwardKinematics(
            self.model, self._data, self._kinematics.configuration(positions)
        )
        return self._data.oMf

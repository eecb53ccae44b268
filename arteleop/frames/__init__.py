"""Frames: rigid transforms with a covariance, the transform graph that joins them, and a
robot's links as frames of a graph.

The site's own graph (the camera's registration, the table and its markers, the tracked bowl)
is :class:`arteleop.scene.SiteFrames`, built on these.
"""

from arteleop.frames.robot_frames import RobotFrames
from arteleop.frames.transform_graph import Edge, EdgeKind, TransformGraph
from arteleop.frames.uncertain_transform import (
    UncertainTransform,
    fuse,
    left_error,
    mean_transform,
)

__all__ = [
    "Edge",
    "EdgeKind",
    "RobotFrames",
    "TransformGraph",
    "UncertainTransform",
    "fuse",
    "left_error",
    "mean_transform",
]

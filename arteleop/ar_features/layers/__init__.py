"""The layers of the operator's view, one module each."""

from arteleop.ar_features.layers.beam import BeamLayer
from arteleop.ar_features.layers.cloud import CloudLayer
from arteleop.ar_features.layers.depth_aids import DepthAidsLayer
from arteleop.ar_features.layers.distance_bar import DistanceBarLayer
from arteleop.ar_features.layers.ghost import GhostLayer, PredictiveGhostLayer
from arteleop.ar_features.layers.grip_bar import GripBarLayer
from arteleop.ar_features.layers.target import TargetLayer

__all__ = [
    "BeamLayer",
    "CloudLayer",
    "DepthAidsLayer",
    "DistanceBarLayer",
    "GhostLayer",
    "GripBarLayer",
    "PredictiveGhostLayer",
    "TargetLayer",
]

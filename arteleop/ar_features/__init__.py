"""The operator's view: the display frame, its AR layers, the modality presets and the viser view.

The view, which pulls in viser's server, is imported on first use: ``import
arteleop.ar_features`` (and so ``arteleop.operator``) stays light. The view's probe and the
browser that takes its pictures are instruments of the tests and benchmarks: they moved to the
repository's ``tests/instruments/`` in 0.3.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from arteleop.ar_features.assets import ViewAssets
from arteleop.ar_features.display_frame import (
    BAR_LABEL_GAP_M,
    DISTANCE_BAR_OFFSET_M,
    DISTANCE_LABEL_STEP_M,
    FOOT_LIFT_M,
    FOOT_RADIUS_M,
    GRIP_BAR_OFFSET_M,
    HEIGHT_LABEL_GAP_M,
    HEIGHT_LABEL_STEP_M,
    LABEL_CLEARANCE_M,
    LABEL_SIZE_M,
    Display,
    DisplayFrame,
    PredictedArm,
)
from arteleop.ar_features.layer import Layer
from arteleop.ar_features.modalities import (
    LAYER_NAMES,
    MODALITIES,
    STUDY_MODALITIES,
    ArCues,
    modality_cues,
)
from arteleop.moved import moved_names

if TYPE_CHECKING:
    from arteleop.ar_features.link_pacer import LinkPacer
    from arteleop.ar_features.view import OperatorView, ViewConfig

_LAZY = {
    "LinkPacer": "arteleop.ar_features.link_pacer",
    "OperatorView": "arteleop.ar_features.view",
    "ViewConfig": "arteleop.ar_features.view",
}

__all__ = [
    "BAR_LABEL_GAP_M",
    "DISTANCE_BAR_OFFSET_M",
    "DISTANCE_LABEL_STEP_M",
    "FOOT_LIFT_M",
    "FOOT_RADIUS_M",
    "GRIP_BAR_OFFSET_M",
    "HEIGHT_LABEL_GAP_M",
    "HEIGHT_LABEL_STEP_M",
    "LABEL_CLEARANCE_M",
    "LABEL_SIZE_M",
    "LAYER_NAMES",
    "MODALITIES",
    "STUDY_MODALITIES",
    "ArCues",
    "Display",
    "DisplayFrame",
    "Layer",
    "LinkPacer",
    "OperatorView",
    "PredictedArm",
    "ViewAssets",
    "ViewConfig",
    "modality_cues",
]


_moved = moved_names(
    "arteleop.ar_features",
    dict.fromkeys(("Received", "ViewProbe"), "tests.instruments.view_probe"),
    until="0.3",
)


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        return getattr(importlib.import_module(_LAZY[name]), name)
    return _moved(name)

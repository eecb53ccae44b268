"""The operator's view: the display frame, its AR layers, the modality presets and the viser view.

The view and the probe, which pull in viser's server and websockets, are imported on first use:
``import arteleop.ar_features`` (and so ``arteleop.operator``) stays light.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from arteleop.ar_features.assets import ViewAssets
from arteleop.ar_features.display_frame import Display, DisplayFrame, PredictedArm
from arteleop.ar_features.layer import Layer
from arteleop.ar_features.modalities import (
    LAYER_NAMES,
    MODALITIES,
    STUDY_MODALITIES,
    ArCues,
    modality_cues,
)

if TYPE_CHECKING:
    from arteleop.ar_features.view import OperatorView, ViewConfig
    from arteleop.ar_features.view_probe import Received, ViewProbe

_LAZY = {
    "OperatorView": "arteleop.ar_features.view",
    "ViewConfig": "arteleop.ar_features.view",
    "Received": "arteleop.ar_features.view_probe",
    "ViewProbe": "arteleop.ar_features.view_probe",
}

__all__ = [
    "LAYER_NAMES",
    "MODALITIES",
    "STUDY_MODALITIES",
    "ArCues",
    "Display",
    "DisplayFrame",
    "Layer",
    "OperatorView",
    "PredictedArm",
    "Received",
    "ViewAssets",
    "ViewConfig",
    "ViewProbe",
    "modality_cues",
]


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        return getattr(importlib.import_module(_LAZY[name]), name)
    raise AttributeError(f"module 'arteleop.ar_features' has no attribute '{name}'")

"""The operator's view (viser), its AR layers and the study's modality presets."""

from arteleop.ar_features.modalities import MODALITIES, ArCues, modality_cues
from arteleop.ar_features.view import OperatorView, ViewConfig
from arteleop.ar_features.view_probe import Received, ViewProbe

__all__ = [
    "MODALITIES",
    "ArCues",
    "OperatorView",
    "Received",
    "ViewConfig",
    "ViewProbe",
    "modality_cues",
]

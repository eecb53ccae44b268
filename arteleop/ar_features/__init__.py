"""AR layers and the study's modality presets (the viser layers come with the AR-view issue)."""

from arteleop.ar_features.modalities import MODALITIES, ArCues, modality_cues

__all__ = ["MODALITIES", "ArCues", "modality_cues"]

"""The layers of the operator's view, one module each."""

from arteleop.ar_features.layers.cloud import CloudLayer

__all__ = ["CloudLayer"]

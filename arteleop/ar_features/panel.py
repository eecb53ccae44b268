"""The view's panel: switch the modality, or single AR layers, live.

"as the trial" draws each frame's own cues (what the operator of the trial sees); choosing a
modality or ticking a layer overrides them in this view until "as the trial" is chosen again.
"""

from __future__ import annotations

from dataclasses import fields

import viser

from arteleop.ar_features.modalities import MODALITIES, ArCues

FOLLOW = "as the trial"
CUSTOM = "custom"
LABELS = {
    "ghost": "ghost robot",
    "beam": "beam",
    "distance_bar": "distance bar",
    "grip_bar": "grip bar",
    "target_mesh": "target mesh",
    "predictive_ghost": "predictive ghost",
}


class ModalityPanel:
    """A modality drop-down and one checkbox per drawn layer."""

    def __init__(self, gui: viser.GuiApi, cues: list[str]) -> None:
        self.cues: ArCues | None = None
        """The panel's choice; None while it follows the frames."""
        with gui.add_folder("AR layers"):
            self._modality = gui.add_dropdown(
                "Modality", (FOLLOW, *MODALITIES, CUSTOM), initial_value=FOLLOW
            )
            self._boxes = {cue: gui.add_checkbox(LABELS[cue], False) for cue in cues}
        self._modality.on_update(self._modality_chosen)
        for box in self._boxes.values():
            box.on_update(self._layer_ticked)

    def follow(self, cues: ArCues) -> None:
        """Show the frames' cues in the checkboxes (while following them)."""
        for cue, box in self._boxes.items():
            box.value = cues.shows(cue)

    def _modality_chosen(self, event: viser.GuiEvent) -> None:
        if event.client_id is None:  # set from here, not by a user
            return
        name = self._modality.value
        if name == FOLLOW:
            self.cues = None
        elif name in MODALITIES:
            self.cues = MODALITIES[name]
            self.follow(self.cues)

    def _layer_ticked(self, event: viser.GuiEvent) -> None:
        if event.client_id is None:
            return
        chosen = {f.name: False for f in fields(ArCues)}
        chosen.update({cue: box.value for cue, box in self._boxes.items()})
        self.cues = ArCues(**chosen)
        named = [name for name, cues in MODALITIES.items() if cues == self.cues]
        self._modality.value = named[0] if named else CUSTOM

"""The view's trial panel: the modality, the trial's timer and state, the last trial's result,
and buttons to reset the robot to its rest pose and to start a trial."""

from __future__ import annotations

from collections.abc import Callable

import viser


class TrialPanel:
    """Read-only fields the application writes, and two buttons it listens to."""

    def __init__(self, gui: viser.GuiApi) -> None:
        with gui.add_folder("Trial"):
            self._modality = gui.add_text("Modality", "", disabled=True)
            self._timer = gui.add_text("Timer", "0.0 s", disabled=True)
            self._state = gui.add_text("State", "starting", disabled=True)
            self._last = gui.add_text("Last trial", "none yet", disabled=True)
            self._reset = gui.add_button("Reset to rest pose")
            self._start = gui.add_button("Start trial")

    def show(self, modality: str, elapsed_s: float, state: str) -> None:
        """The running trial: its modality, its timer (s) and its state in words."""
        self._set(self._modality, modality)
        self._set(self._timer, f"{elapsed_s:.1f} s")
        self._set(self._state, state)

    def finished(self, state: str, summary: str) -> None:
        """A trial has ended: its outcome as the state, and its result."""
        self._set(self._state, state)
        self._set(self._last, summary)

    def on_reset(self, callback: Callable[[], None]) -> None:
        self._reset.on_click(lambda _: callback())

    def on_start(self, callback: Callable[[], None]) -> None:
        self._start.on_click(lambda _: callback())

    @staticmethod
    def _set(handle: viser.GuiTextHandle, text: str) -> None:
        if handle.value != text:  # each change is a message to every browser
            handle.value = text

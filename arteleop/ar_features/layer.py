"""One layer of the operator's view: the unit that AR features are made of.

A layer owns its viser scene handles and redraws them from a :class:`DisplayFrame`; the modality
table (:mod:`arteleop.ar_features.modalities`) says which layers are on. In the spirit of mink's
``Task``: one small abstract method, and the view composes the layers.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import fields
from typing import ClassVar

from arteleop.ar_features.display_frame import DisplayFrame
from arteleop.ar_features.modalities import ArCues
from arteleop.errors import ConfigurationError


class Layer(ABC):
    """A drawn layer of the view.

    Subclasses set ``cue`` to the :class:`ArCues` field that switches them on (None: always
    drawn; or another switch of the frame's, by overriding :meth:`shown`), implement
    :meth:`update` and :meth:`_set_visible`.
    """

    cue: ClassVar[str | None] = None

    def __init_subclass__(cls, **kwargs: object) -> None:
        super().__init_subclass__(**kwargs)
        names = [f.name for f in fields(ArCues)]
        if cls.cue is not None and cls.cue not in names:
            raise ConfigurationError(
                f"{cls.__name__}.cue = '{cls.cue}' is not an AR cue; valid cues: {names}"
            )

    def __init__(self) -> None:
        self._visible: bool | None = None

    def shown(self, frame: DisplayFrame) -> bool:
        """Whether ``frame`` shows the layer: as its cues say."""
        return frame.cues.shows(self.cue)

    def draw(self, frame: DisplayFrame) -> None:
        """Show or hide the layer as :meth:`shown` says, and redraw it when shown."""
        on = self.shown(frame)
        if on != self._visible:
            self._set_visible(on)
            self._visible = on
        if on:
            self.update(frame)

    @abstractmethod
    def update(self, frame: DisplayFrame) -> None:
        """Redraw the layer's handles from ``frame``."""

    @abstractmethod
    def _set_visible(self, visible: bool) -> None:
        """Show or hide every handle the layer owns."""

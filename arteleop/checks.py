"""Range checks of a configuration's numbers, with one form of message:
``Owner.field = value: expected <range>.``"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

from arteleop.errors import ArteleopError, ConfigurationError


@dataclass(frozen=True)
class Bounds:
    """The finite values a field admits: ``low <= value <= high`` (``low < value`` if
    ``above``), said in the message as ``low-high (what)``, ``> low and <= high (what)``,
    ``> low`` or ``>= low``, or as ``text`` where given.

    Attributes:
        low: The smallest value admitted (or the bound above which values are admitted).
        high: The largest value admitted.
        what: The unit or kind of value, said in brackets after a range.
        above: ``low`` itself is refused.
        text: What the message says is expected, in place of the range.
    """

    low: float = -math.inf
    high: float = math.inf
    what: str = ""
    above: bool = False
    text: str | None = None

    def admits(self, value: float) -> bool:
        """Whether ``value`` is a finite number within the bounds."""
        if not math.isfinite(value) or value > self.high:
            return False
        return value > self.low if self.above else value >= self.low

    def __str__(self) -> str:
        if self.text is not None:
            return self.text
        if math.isinf(self.high):
            return f"{'>' if self.above else '>='} {self.low}"
        said = f"> {self.low} and <= {self.high}" if self.above else f"{self.low}-{self.high}"
        return f"{said} ({self.what})" if self.what else said


def check_fields(
    config: object,
    bounds: Mapping[str, Bounds],
    error: type[ArteleopError] = ConfigurationError,
) -> None:
    """Raise ``error`` naming the first field of ``config`` outside its ``bounds``."""
    owner = type(config).__name__
    for name, allowed in bounds.items():
        value = getattr(config, name)
        if not allowed.admits(value):
            raise error(f"{owner}.{name} = {value!r}: expected {allowed}.")

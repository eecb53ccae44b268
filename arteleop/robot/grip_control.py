"""The operator's pinch grip (0..1) to a gripper command, with hysteresis."""

from __future__ import annotations

from dataclasses import dataclass

from arteleop.errors import ConfigurationError


@dataclass(frozen=True)
class GripHysteresis:
    """Close when the grip rises to ``close_at``; open when it falls to ``open_at``.

    The band keeps sensor noise around one threshold from chattering the gripper.
    """

    close_at: float = 0.6
    open_at: float = 0.4

    def __post_init__(self) -> None:
        if not 0.0 < self.open_at < self.close_at < 1.0:
            raise ConfigurationError(
                f"GripHysteresis needs 0 < open_at ({self.open_at}) < close_at "
                f"({self.close_at}) < 1"
            )


class GripCommand:
    """Latched open/closed command: 0 (open) or 1 (closed)."""

    def __init__(self, hysteresis: GripHysteresis | None = None) -> None:
        self.hysteresis = hysteresis or GripHysteresis()
        self.closed = False

    def update(self, grip: float) -> float:
        """Closure command for the latest grip value."""
        if not self.closed and grip >= self.hysteresis.close_at:
            self.closed = True
        elif self.closed and grip <= self.hysteresis.open_at:
            self.closed = False
        return 1.0 if self.closed else 0.0

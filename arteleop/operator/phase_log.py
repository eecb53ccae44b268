"""When the synthetic operator began and ended each of a task's phases: what a benchmark times
(a pointing movement from its first submovement to the selection)."""

from __future__ import annotations

from dataclasses import dataclass, replace


@dataclass(frozen=True)
class PhaseRecord:
    """One pass through a task's phase (s): when it began, when its first movement started
    (None if it made none) and when it ended (None while under way)."""

    name: str
    start_s: float
    first_move_s: float | None = None
    end_s: float | None = None


class PhaseLog:
    """Every pass through one of a task's phases, in order."""

    def __init__(self) -> None:
        self.records: list[PhaseRecord] = []

    def enter(self, name: str | None, time_s: float) -> None:
        """The phase under way ends at ``time_s`` (s); the task's phase ``name`` begins (None:
        the operator is outside the task)."""
        if self._open():
            self.records[-1] = replace(self.records[-1], end_s=time_s)
        if name is not None:
            self.records.append(PhaseRecord(name, time_s))

    def moved(self, start_s: float) -> None:
        """A submovement starts at ``start_s`` (s) in the phase under way."""
        if self._open() and self.records[-1].first_move_s is None:
            self.records[-1] = replace(self.records[-1], first_move_s=start_s)

    def _open(self) -> bool:
        return bool(self.records) and self.records[-1].end_s is None

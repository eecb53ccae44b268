"""When the synthetic operator began and ended each of a task's phases, and what it did in them:
what a benchmark times (a pointing movement from its first submovement to the selection) and
where that time goes."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from types import MappingProxyType

ACTIVITIES = ("move", "watch", "look", "wait")
"""What the operator may be doing: moving its hand (from deciding to, its motor delay included),
watching the display for the gripper to come to rest, looking (glance after glance), or waiting
(a grip, a phase's start)."""


@dataclass(frozen=True)
class PhaseRecord:
    """One pass through a task's phase (s): when it began, when its first movement started
    (None if it made none) and when it ended (None while under way).

    From the first movement's start on, it also holds the time spent in each of
    :data:`ACTIVITIES` (s; they add up to the phase's time since that start), the submovements
    started after the first (corrections, in flight or after a look) and the looks begun.
    """

    name: str
    start_s: float
    first_move_s: float | None = None
    end_s: float | None = None
    activity_s: Mapping[str, float] = field(
        default_factory=lambda: MappingProxyType(dict.fromkeys(ACTIVITIES, 0.0))
    )
    corrections: int = 0
    looks: int = 0


class PhaseLog:
    """Every pass through one of a task's phases, in order."""

    def __init__(self) -> None:
        self.records: list[PhaseRecord] = []
        # The open record's activity times, which it shows read-only: counted in place at every
        # sample, not copied into a new record.
        self._activity_s: dict[str, float] = {}

    def enter(self, name: str | None, time_s: float) -> None:
        """The phase under way ends at ``time_s`` (s); the task's phase ``name`` begins (None:
        the operator is outside the task)."""
        if self._open():
            self.records[-1] = replace(self.records[-1], end_s=time_s)
        if name is not None:
            self._activity_s = dict.fromkeys(ACTIVITIES, 0.0)
            activity_s = MappingProxyType(self._activity_s)
            self.records.append(PhaseRecord(name, time_s, activity_s=activity_s))

    def moved(self, start_s: float) -> None:
        """A submovement starts at ``start_s`` (s) in the phase under way."""
        if not self._open():
            return
        record = self.records[-1]
        if record.first_move_s is None:
            self.records[-1] = replace(record, first_move_s=start_s)
        else:
            self.records[-1] = replace(record, corrections=record.corrections + 1)

    def looked(self, time_s: float) -> None:
        """A look begins at ``time_s`` (s) in the phase under way."""
        if self._moving_since(time_s):
            self.records[-1] = replace(self.records[-1], looks=self.records[-1].looks + 1)

    def spent(self, activity: str, from_s: float, to_s: float) -> None:
        """The operator did ``activity`` (one of :data:`ACTIVITIES`) from ``from_s`` to ``to_s``
        (s): counted from the phase's first movement on."""
        if not self._moving_since(to_s):
            return
        first_move_s = self.records[-1].first_move_s
        assert first_move_s is not None
        self._activity_s[activity] += max(0.0, to_s - max(from_s, first_move_s))

    def _moving_since(self, time_s: float) -> bool:
        """A phase is under way and its first movement had started by ``time_s`` (s)."""
        if not self._open():
            return False
        first = self.records[-1].first_move_s
        return first is not None and time_s >= first

    def _open(self) -> bool:
        return bool(self.records) and self.records[-1].end_s is None

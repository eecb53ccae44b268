"""Where a phase's time goes: the operator's activities from its first movement on, its
corrections and its looks."""

from __future__ import annotations

import pytest

from arteleop.operator import ACTIVITIES
from arteleop.operator.simulated.phase_log import PhaseLog
from arteleop.operator.simulated.synthetic import _Mode


def test_a_phase_counts_its_activities_from_its_first_movement() -> None:
    log = PhaseLog()
    log.enter("point", 1.0)
    log.looked(1.0)  # the look that plans the movement: before it, not counted
    log.spent("look", 1.0, 1.3)
    log.moved(1.37)  # decided at 1.3, moving after the motor delay
    log.spent("move", 1.3, 1.5)  # counted from 1.37
    log.moved(1.45)  # a correction in flight
    log.spent("move", 1.5, 2.0)
    log.spent("watch", 2.0, 2.4)
    log.looked(2.4)
    log.spent("look", 2.4, 2.9)
    log.enter("select", 2.9)
    log.spent("wait", 2.9, 3.2)  # the next phase's, which has not moved
    point, select = log.records
    assert point.activity_s == pytest.approx({"move": 0.63, "watch": 0.4, "look": 0.5, "wait": 0})
    assert sum(point.activity_s.values()) == pytest.approx(point.end_s - point.first_move_s)
    assert (point.corrections, point.looks) == (1, 1)
    assert sum(select.activity_s.values()) == 0 and select.first_move_s is None


def test_the_activities_are_the_operators_modes() -> None:
    assert {m.value for m in _Mode} == set(ACTIVITIES)

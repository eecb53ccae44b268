"""A task of a user's own, as a study names it (``task = "tests.teleop.squeeze_task:SQUEEZE"``):
bring the gripper 10 cm over the bowl and squeeze; the squeeze ends the trial, a success."""

from __future__ import annotations

import numpy as np

from arteleop.operator import Action, Goal, OperatorTraits, Perceived, TaskPhase
from arteleop.operator.simulated.tasks import relative_goal
from arteleop.scene import BowlTracker
from arteleop.teleop import Outcome, TaskMonitor, TaskSite, TrialTask

ABOVE_M = 0.10
"""How far over the bowl the gripper is brought (m)."""


class Squeeze:
    """The participant's side: over the bowl, then squeeze."""

    phases = (TaskPhase("over"), TaskPhase("squeeze", Action.CLOSE))
    ends_trial = True
    aims_gripper = False

    def __init__(self, site: TaskSite) -> None:
        self.rest_gripper_m = site.rest_gripper_m

    def criterion_m(self, phase: TaskPhase, traits: OperatorTraits) -> float | None:
        return 0.02

    def goal(self, phase: TaskPhase, seen: Perceived) -> Goal | None:
        if seen.bowl_m is None:
            return None
        return relative_goal(seen.bowl_m + np.array([0.0, 0.0, ABOVE_M]), seen)

    def gripped(self, phase: TaskPhase, seen: Perceived) -> None:
        pass

    def setback(self, phase: TaskPhase, seen: Perceived) -> str | None:
        return None


class SqueezeMonitor(TaskMonitor):
    """The site's side: a trial whose participant squeezed and stopped succeeded."""

    def operator_stopped(self) -> Outcome:
        return Outcome.SUCCESS if self.grasp_attempts else Outcome.OPERATOR_STOPPED


SQUEEZE = TrialTask("squeeze", Squeeze, lambda ws: SqueezeMonitor(ws, BowlTracker(ws.bowl)))

NOT_A_TASK = "squeeze"
"""Something else under a name a study could give."""

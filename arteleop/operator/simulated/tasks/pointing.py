"""A Fitts pointing task: the simulated participant's calibration task
(docs/explanation/operator-model.md, ``benchmarks/bench_fitts.py``).

The person brings the gripper over a start point, then over a target circle drawn on the table
(its diameter the target's width), and selects it by closing the gripper, which ends the trial.
The pointing movement is judged as a person pointing judges it: the circle, centred on by eye,
against the gripper above it (the task aims the gripper itself); its criterion is half the
target's width (the person aims to end inside the circle).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from arteleop.operator.simulated.perception import Perceived
from arteleop.operator.simulated.tasks.task import (
    Action,
    Goal,
    TaskPhase,
    planar_goal,
)
from arteleop.operator.simulated.traits import OperatorTraits

TO_START = TaskPhase("reach")  # over the start point
POINT = TaskPhase("point")  # the pointing movement, over the target
SELECT = TaskPhase("select", Action.CLOSE)


class PointingTask:
    """One pointing trial (base frame, m).

    The start and the target are where the display draws them, the start's cross and the
    target's circle (``DisplayFrame.start_m``, ``DisplayFrame.target_m``): the person knows them
    only as seen.

    Args:
        width_m: The target's width: the circle's diameter (m).
        rest_gripper_m: Where the gripper waits at rest, to align the hand before engaging.
        height_m: How high over the table the gripper points (m).
        start_clearance_m: How near the start point is near enough (m), as the grasp's
            clearance is: times the person's share of it.
    """

    phases = (TO_START, POINT, SELECT)
    ends_trial = True
    aims_gripper = True
    marks = ("start",)

    def __init__(
        self,
        *,
        width_m: float,
        rest_gripper_m: ArrayLike,
        height_m: float = 0.05,
        start_clearance_m: float = 0.019,
    ) -> None:
        self.width_m = width_m
        self.rest_gripper_m = np.asarray(rest_gripper_m, dtype=np.float64)
        self.height_m = height_m
        self.start_clearance_m = start_clearance_m

    def criterion_m(self, phase: TaskPhase, traits: OperatorTraits) -> float | None:
        if phase is TO_START:
            return self.start_clearance_m * traits.grasp_criterion_scale
        return self.width_m / 2 if phase is POINT else None

    def goal(self, phase: TaskPhase, seen: Perceived) -> Goal | None:
        up = np.array([0.0, 0.0, self.height_m])
        if phase is POINT:
            # The circle as the cloud shows it, centred on by eye.
            return planar_goal(seen.target_m + up, seen, None)
        start = seen.marks.get("start")
        if start is None:
            return None  # no start drawn: nothing to aim at
        # The cross as the cloud shows it, against the gripper over it, and the height with it:
        # the pointing movement starts level with where it ends.
        return Goal(start.mark_m + up, start.cov, "xyz", seen.gripper_seen, start.fixations)

    def gripped(self, phase: TaskPhase, seen: Perceived) -> None:
        """Nothing to remember: the selection ends the task."""

    def setback(self, phase: TaskPhase, seen: Perceived) -> str | None:
        return None

"""What a person sees of a trial's outcome on the display it ended on: whether it missed.

Where nobody tells a miss (the original study's participants saw only the camera's view), the
person learns it from a last look at the display once the task is done: in the pick-and-place,
the bowl resting off the target. It judges the task's outcome as it judged the phase that made
it (the task's ``outcome_phase``: the placement, in the table's plane), with the same eyes and
cues, against the criterion it accepted that phase at (loosened by the effort it had spent: what
it settled for is no miss to it), and counts a miss only where it is as sure that the outcome
is outside it as it must be sure, to stop, that it is inside (its ``confidence``): a miss it
cannot see on the display it does not learn of, and one the display shows clearly it does. A
trial that ended before the bowl was let go on the table (in time, or dropped) is a miss it
knows without looking (:func:`~arteleop.study.protocol.run_planned_trial`). What it learns it
carries to the next trial (:class:`~arteleop.operator.SeenOutcomes`).
"""

from __future__ import annotations

from collections.abc import Mapping

from arteleop.operator.simulated.belief import probability_within
from arteleop.operator.simulated.perception import Perceived
from arteleop.operator.simulated.tasks import Task
from arteleop.operator.simulated.traits import OperatorTraits


def sure_missed(
    task: Task,
    seen: Perceived,
    traits: OperatorTraits,
    error_scale: float,
    accepted_m: Mapping[str, float],
) -> bool:
    """Whether a glance at the display the trial ended on (``seen``) leaves the person sure that
    the task's outcome missed: the error of the task's ``outcome_phase``'s goal within the
    criterion the person accepted the phase at (``accepted_m``, m, by phase name: loosened by
    the effort it had spent; the task's for the person if it never accepted it) with
    probability at most ``1 - confidence``, the judgement's covariance believed short by
    ``error_scale``, in the axes the phase is judged in. False for a task without an
    ``outcome_phase`` (its outcome is told, or not judged) and where the display never showed
    what the goal is judged against."""
    phase = getattr(task, "outcome_phase", None)
    if phase is None:
        return False
    goal = task.goal(phase, seen)
    criterion_m = accepted_m.get(phase.name, task.criterion_m(phase, traits))
    if goal is None or criterion_m is None:
        return False
    error = goal.gripper_m - seen.gripper_m  # in the plane, whatever the hand's height now
    sure_within = probability_within(error, error_scale * goal.cov_m2, criterion_m, goal.axes)
    return sure_within <= 1.0 - traits.confidence

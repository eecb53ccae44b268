"""What a task asks of the synthetic operator, apart from how the operator does it.

A task is a sequence of phases (:class:`TaskPhase`). In a phase that moves, the operator brings
the gripper to the phase's goal, which the task judges from each glance at the display
(:meth:`Task.goal`), until it is sure the error is within the task's criterion for the phase
(:meth:`Task.criterion_m`); in a phase that grips, it squeezes or releases the pinch sensor and
tells the task what it saw (:meth:`Task.gripped`). A look may show that the task went wrong
(a bowl left behind): the task names the phase to go back to (:meth:`Task.setback`). The
mechanism (looks, belief, submovements, homing in, the display's lag) is the operator's and the
same for every task (:class:`~arteleop.operator.SyntheticOperator`).

A task object is made for one trial: it keeps what the person knows and remembers of the task's
objects while doing it (where the bowl was last seen, where the hand took it).
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum
from typing import NamedTuple, Protocol

import numpy as np
from numpy.typing import NDArray

from arteleop.errors import ConfigurationError
from arteleop.operator.simulated.perception import Perceived
from arteleop.operator.simulated.traits import OperatorTraits


class Action(Enum):
    """What the operator does in a phase."""

    MOVE = "move"  # bring the gripper to the phase's goal, to within the criterion
    CLOSE = "close"  # squeeze the pinch sensor
    OPEN = "open"  # release it


@dataclass(frozen=True)
class TaskPhase:
    """One phase of a task.

    Attributes:
        name: The phase's name, as the operator reports it (``OperatorOutput.phase``).
        action: What the operator does in it.
    """

    name: str
    action: Action = Action.MOVE


class Goal(NamedTuple):
    """A phase's goal as one glance at the display shows it (base frame).

    Attributes:
        gripper_m: Where the gripper should be (m), as the person judges it.
        cov_m2: (3, 3) covariance the person believes its judgement of the error between the
            gripper and the goal has (m^2): its precision, not its bias.
        axes: ``"xyz"``, or ``"xy"``: the error is judged in the table's plane, once the height
            is within the operator's gross criterion.
        visible: The display shows both ends of the error, so the operator can home in on the
            goal during a movement.
        fixations: The fixations one glance at the error takes (:class:`Perceived`).
    """

    gripper_m: NDArray[np.float64]
    cov_m2: NDArray[np.float64]
    axes: str
    visible: bool
    fixations: int = 1


class Task(Protocol):
    """What a task asks of the operator; see the module's description.

    Attributes:
        phases: The task's phases in order, after the operator has engaged the robot.
        rest_gripper_m: Where the gripper rests before the task (base frame, m): the operator
            aligns its hand on it to engage.
        ends_trial: The operator's last phase ends the trial (a selection); otherwise the site
            judges when it has ended (the bowl found at rest at its place).
        aims_gripper: The task brings the gripper itself onto marks drawn on the table
            (pointing at the target from the start), not an object it holds: the target's
            circle, and the marks it judges (``marks``), are judged against the gripper, not
            the object (``Perceived.target_m``, ``Perceived.marks``).
        marks: The marks the task judges besides the target, by name
            (:data:`~arteleop.operator.simulated.mark_judging.MARK_JUDGEMENTS`: ``"start"``, the
            start's cross); a task without the attribute judges none. What is seen of them is
            ``Perceived.marks``: a task's own judgements are not fields of every glance.
        outcome_phase: The phase whose goal, judged on the display the trial ended on, says
            whether the person sees that it missed (:mod:`~arteleop.operator.simulated.outcome`);
            a task without the attribute, or with None, leaves its misses to be told.
    """

    phases: tuple[TaskPhase, ...]
    rest_gripper_m: NDArray[np.float64]
    ends_trial: bool
    aims_gripper: bool
    marks: tuple[str, ...]

    def criterion_m(self, phase: TaskPhase, traits: OperatorTraits) -> float | None:
        """The person's criterion for the phase's goal (m) before urgency loosens it; None for a
        phase without a precision demand, which the operator's gross criterion judges and which
        it does not home in on."""
        ...

    def goal(self, phase: TaskPhase, seen: Perceived) -> Goal | None:
        """The phase's goal from one glance; None while the display has not yet shown what the
        goal is judged against. The task remembers what the glance showed."""
        ...

    def gripped(self, phase: TaskPhase, seen: Perceived) -> None:
        """The operator has squeezed or released the pinch sensor (``phase``'s action), seeing
        ``seen``."""
        ...

    def setback(self, phase: TaskPhase, seen: Perceived) -> str | None:
        """The name of the phase to go back to, with the hand open, when a look in ``phase``
        shows the task went wrong; None when it did not."""
        ...


def relative_goal(gripper_m: NDArray[np.float64], seen: Perceived) -> Goal:
    """A goal judged as the gripper's place relative to the bowl (grasping, or any goal set
    from the bowl): seen whole where the display shows the gripper and the bowl."""
    shown = seen.gripper_seen and seen.bowl_m is not None
    return Goal(gripper_m, seen.gripper_cov, "xyz", shown, seen.gripper_fixations)


def planar_goal(
    gripper_m: NDArray[np.float64], seen: Perceived, held_cov_m2: NDArray[np.float64] | None
) -> Goal:
    """A goal judged in the table's plane against the target (placing, or pointing at it).
    Where it was judged from the gripper (a bowl in hand hidden), the bowl's place in the hand,
    with covariance ``held_cov_m2`` (None: nothing held), adds its own uncertainty."""
    cov = seen.target_cov
    if seen.target_by_gripper and held_cov_m2 is not None:
        cov = cov + held_cov_m2
    shown = seen.bowl_m is not None or (seen.target_by_gripper and seen.gripper_seen)
    return Goal(gripper_m, cov, "xy", shown and seen.gripper_seen, seen.target_fixations)


def phase_named(task: Task, name: str) -> TaskPhase:
    """The phase of ``task`` called ``name``."""
    for phase in task.phases:
        if phase.name == name:
            return phase
    names = ", ".join(p.name for p in task.phases)
    raise ConfigurationError(f"The task has no phase {name!r}; its phases: {names}.")

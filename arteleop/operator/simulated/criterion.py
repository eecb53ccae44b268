"""How close to a phase's goal the operator demands to be, and how sure it is of being there."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from arteleop.operator.simulated.belief import probability_within
from arteleop.operator.simulated.own_errors import believed_error_scale
from arteleop.operator.simulated.params import OperatorParams
from arteleop.operator.simulated.tasks import Goal, Task, TaskPhase
from arteleop.operator.simulated.traits import OperatorTraits


class PhaseCriterion:
    """The criterion (m) of the task's phase under way: the task's for the phase, or
    ``gross_criterion_m`` for a movement without a precision demand (and outside the task),
    loosened by the effort spent correcting since the phase's primary movement arrived; its
    judgement's covariance believed short by :attr:`error_scale`."""

    def __init__(self, task: Task, traits: OperatorTraits, params: OperatorParams) -> None:
        self._task = task
        self._traits = traits
        self._gross_m = params.gross_criterion_m
        self.error_scale = believed_error_scale(
            params.seen_outcomes, traits.confidence, params.own_error_prior_sd
        )
        """What the misses of its earlier trials taught the operator of its judgement: the
        factor (at least 1) its covariance falls short by, the same all trial."""
        self._phase: TaskPhase | None = None
        self._correcting_from_s: float | None = None  # the primary's arrival in this phase
        self.accepted_m: dict[str, float] = {}
        """The criterion (m) each of the task's phases was last accepted at, by name."""

    def enter(self, phase: TaskPhase | None) -> None:
        """A phase begins (None: one of the operator's own): no effort spent in it yet."""
        self._phase = phase
        self._correcting_from_s = None

    def arrived(self, t: float) -> None:
        """The phase's movement has come to rest at ``t`` (s): correcting starts, once."""
        if self._correcting_from_s is None:
            self._correcting_from_s = t

    def accept(self, t: float) -> None:
        """The operator is sure enough at ``t`` (s) that the phase's goal is met."""
        if self._phase is not None:
            self.accepted_m[self._phase.name] = self.at(t)

    def task_m(self) -> float | None:
        """The task's own criterion for the phase (m); None where it demands no precision."""
        phase = self._phase
        return None if phase is None else self._task.criterion_m(phase, self._traits)

    def at(self, t: float) -> float:
        """The criterion at ``t`` (s), loosened by the phase's effort so far (m)."""
        c0 = self.task_m()
        return (self._gross_m if c0 is None else c0) * self._loosening(t)

    def _loosening(self, t: float) -> float:
        """How much the criterion has grown with the effort spent correcting in this phase:
        from the arrival of its primary movement, which was planned to meet the criterion."""
        if self._correcting_from_s is None:
            return 1.0
        return 1.0 + (t - self._correcting_from_s) / self._traits.urgency_s

    def sure_within(
        self,
        t: float,
        error: NDArray[np.float64],
        goal: Goal,
        cov_m2: NDArray[np.float64] | None = None,
    ) -> float:
        """How sure the operator is that ``error`` (m) is within the criterion at ``t``,
        believing it has the covariance ``cov_m2`` (m^2; the goal's judgement's by default)
        times its error scale. Judged in the table's plane, the height must first be reached, as
        any movement without a precision demand (within ``gross_criterion_m``)."""
        if goal.axes == "xy" and abs(error[2]) > self._gross_m:
            return 0.0
        cov = self.error_scale * (goal.cov_m2 if cov_m2 is None else cov_m2)
        return probability_within(error, cov, self.at(t), goal.axes)

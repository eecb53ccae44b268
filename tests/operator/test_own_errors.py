"""What the operator learns of its own errors from the outcomes it sees: a seen miss makes the
next trial's criterion stricter; hits alone change nothing."""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from arteleop.errors import ConfigurationError
from arteleop.operator import OperatorParams, OperatorTraits, PointingTask
from arteleop.operator.simulated.criterion import PhaseCriterion
from arteleop.operator.simulated.own_errors import SeenOutcomes, believed_error_scale
from arteleop.operator.simulated.tasks import Goal
from arteleop.operator.simulated.tasks.pointing import POINT

CONFIDENCE = OperatorTraits().confidence


def _criterion(seen: SeenOutcomes) -> PhaseCriterion:
    task = PointingTask(width_m=0.02, rest_gripper_m=np.zeros(3))
    criterion = PhaseCriterion(task, OperatorTraits(), OperatorParams(seen_outcomes=seen))
    criterion.enter(POINT)
    return criterion


def test_after_a_seen_miss_the_next_trials_criterion_is_stricter() -> None:
    """An error the operator was sure enough of before (its judgement's SD 2 mm, 6 mm off the
    middle of a circle of 10 mm radius) no longer is, after one miss in its first five trials."""
    goal = Goal(np.zeros(3), np.diag([4e-6, 4e-6, 4e-6]), "xy", True)
    error = np.array([0.006, 0.0, 0.0])
    before = _criterion(SeenOutcomes(5, 0)).sure_within(0.0, error, goal)
    after = _criterion(SeenOutcomes(5, 1)).sure_within(0.0, error, goal)
    assert before >= CONFIDENCE > after


@given(st.integers(0, 500))
def test_without_misses_the_criterion_does_not_drift(trials: int) -> None:
    seen = SeenOutcomes(trials, 0)
    assert believed_error_scale(seen, CONFIDENCE, 0.69) == 1.0
    assert _criterion(seen).error_scale == 1.0


def test_with_a_flat_prior_the_scale_makes_the_expected_miss_rate_the_seen_one() -> None:
    """(1 - c)^(1 / lambda) = m / n: 4 misses in 20 at c = 0.95 is lambda = ln 0.05 / ln 0.2."""
    scale = believed_error_scale(SeenOutcomes(20, 4), 0.95, prior_sd=100.0)
    assert scale == pytest.approx(math.log(0.05) / math.log(0.2), rel=2e-3)


@given(st.integers(1, 200), st.data())
def test_more_misses_teach_more_care_and_more_hits_less(trials: int, data: st.DataObject) -> None:
    misses = data.draw(st.integers(1, trials))
    scale = believed_error_scale(SeenOutcomes(trials, misses), CONFIDENCE, 0.69)
    assert scale >= 1.0
    if misses < trials:
        assert believed_error_scale(SeenOutcomes(trials, misses + 1), CONFIDENCE, 0.69) >= scale
    assert believed_error_scale(SeenOutcomes(trials + 1, misses), CONFIDENCE, 0.69) <= scale


def test_misses_at_the_rate_meant_move_the_scale_little() -> None:
    """5 misses in 100 at c = 0.95 is what the operator meant: within 10 % of trusting its
    judgement; four times that rate, nearly the flat prior's ln 0.05 / ln 0.2."""
    assert believed_error_scale(SeenOutcomes(100, 5), 0.95, 0.69) < 1.1
    assert believed_error_scale(SeenOutcomes(100, 20), 0.95, 0.69) > 1.7


@pytest.mark.parametrize(
    ("make", "message"),
    [
        (lambda: SeenOutcomes(2, 3), "SeenOutcomes.misses = 3: expected 0 to trials (2)."),
        (lambda: SeenOutcomes(-1, 0), "SeenOutcomes.trials = -1: expected >= 0."),
        (lambda: OperatorParams(own_error_prior_sd=0.0),
         "OperatorParams.own_error_prior_sd = 0.0: expected > 0."),
    ],
)  # fmt: skip
def test_impossible_outcomes_and_priors_are_refused(make, message: str) -> None:
    with pytest.raises(ConfigurationError) as err:
        make()
    assert str(err.value) == message

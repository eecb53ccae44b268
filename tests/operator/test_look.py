"""When a look ends, and with what: the verdict after each glance."""

import pytest

from arteleop.operator import OperatorTraits
from arteleop.operator.simulated.look import Look


def _verdicts(variances_m2: list[float], sure: float, judged_within: bool) -> list[bool | None]:
    look = Look(OperatorTraits(), max_look_s=10.0)
    look.start(0.0)
    verdicts = []
    for k, variance in enumerate(variances_m2):
        look.glanced(0.3 * k, 0.3)
        verdicts.append(look.verdict(0.3 * (k + 1), sure, variance, judged_within))
    return verdicts


@pytest.mark.parametrize("judged_within", [True, False])
def test_a_look_unsure_either_way_goes_on_while_glances_help(judged_within: bool) -> None:
    # Fresh noise averaging away: the variance halves with each glance.
    assert _verdicts([4e-4, 2e-4, 1.33e-4], 0.5, judged_within) == [None, None, None]


def test_when_looking_no_longer_helps_an_error_judged_within_the_criterion_is_accepted() -> None:
    # A remembered mark: its variance grows glance by glance, and no look makes it surer; nor
    # would a correction of an error already within the criterion.
    assert _verdicts([4e-4, 4.2e-4], 0.5, judged_within=True) == [None, True]
    assert _verdicts([4e-4, 4.2e-4], 0.5, judged_within=False) == [None, False]


def test_sure_either_way_decides_whatever_the_judged_error() -> None:
    assert _verdicts([4e-4], 0.99, judged_within=False) == [True]
    assert _verdicts([4e-4], 0.01, judged_within=True) == [False]


@pytest.mark.parametrize("judged_within", [True, False])
def test_a_look_cut_at_its_longest_decides_on_the_judged_error(judged_within: bool) -> None:
    # Glances still helping (the variance halving), unsure either way, until the look's
    # longest: an error judged within the criterion is accepted, as when glances no longer
    # help; correcting it would leave the next look as unsure (a look averages afresh).
    look = Look(OperatorTraits(), max_look_s=0.5)
    look.start(0.0)
    verdicts = []
    for k, variance in enumerate([4e-4, 2e-4]):
        look.glanced(0.3 * k, 0.3)
        verdicts.append(look.verdict(0.3 * (k + 1), 0.5, variance, judged_within))
    assert verdicts == [None, judged_within]

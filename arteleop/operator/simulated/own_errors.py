"""What a person learns of its own errors from the outcomes it sees: misses make it more careful.

The operator stops correcting once it is sure enough (its ``confidence``, c) that the error is
within its criterion, believing the error ``N(e_hat, Sigma)``: ``Sigma`` is its judgement's
precision, and it does not know its lasting errors (a depth scale, a stale frame). A person who
sees it misses more often than it meant to infers that its errors are larger than it believed,
by a factor ``lambda`` on ``Sigma``, and from then on demands more before it stops: people told
to be fast and accurate keep their error rate near 4 % (Soukoreff & MacKenzie 2004), and take
their own motor variability into account when they aim (Trommershäuser, Maloney & Landy
2003); docs/explanation/operator-model.md says what is assumed.

Stopping at the criterion's edge of certainty, centred in the table's plane, an operator whose
true covariance is ``lambda Sigma`` misses with probability ``q(lambda) = (1 - c)^(1 / lambda)``
(two axes: ``P(|e| > r) = exp(-r^2 / 2 sigma^2)``). After ``m`` misses in ``n`` seen outcomes
it takes the most probable ``lambda >= 1`` under a prior on ``ln lambda`` that is half-normal
about 0 (it believes its own judgement until shown otherwise):

    ln p(lambda | m, n) = -(ln lambda)^2 / (2 s^2) + m ln q + (n - m) ln (1 - q) + const

Hits alone keep ``lambda`` at 1: its care does not drift without a miss. Misses at the rate it
meant (``1 - c``) move ``lambda`` little; at c = 0.95 a miss rate four times that, to about 1.9
once many outcomes are seen (at c = 0.8, to 7; at 0.995, to 1.35). The scale is sought up to 64:
misses on every trial for long reach that bound. It scales all the operator believes of its
error, the prediction in flight too: less sure that a predicted miss is one, it corrects fewer
in flight, and more after a look.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from arteleop.checks import Bounds, check_fields

_LN_LAMBDA = np.linspace(0.0, math.log(64.0), 4001)
"""The grid ``ln lambda`` is sought on: up to 64 times the believed covariance, in steps of
0.1 %."""


@dataclass(frozen=True)
class SeenOutcomes:
    """The outcomes of its earlier trials a person has seen: how many, and how many missed.

    Attributes:
        trials: Trials whose outcome it saw.
        misses: Of those, the ones it saw missed (in pointing: a selection outside the
            circle, or none in time).
    """

    trials: int = 0
    misses: int = 0

    def __post_init__(self) -> None:
        of_trials = Bounds(0, self.trials, text=f"0 to trials ({self.trials})")
        check_fields(self, {"trials": Bounds(0), "misses": of_trials})

    def after(self, missed: bool) -> SeenOutcomes:
        """These outcomes and one more, ``missed`` or not."""
        return SeenOutcomes(self.trials + 1, self.misses + int(missed))


def believed_error_scale(outcomes: SeenOutcomes, confidence: float, prior_sd: float) -> float:
    """The factor ``lambda >= 1`` the person believes its judgement's covariance short by, after
    ``outcomes``, stopping at ``confidence`` (probability), its prior on ``ln lambda`` a
    half-normal of SD ``prior_sd``: the posterior's mode (see the module's docstring). Exactly 1
    without a miss."""
    if outcomes.misses == 0:
        return 1.0
    m, n = outcomes.misses, outcomes.trials
    ln_q = math.log(1.0 - confidence) * np.exp(-_LN_LAMBDA)
    log_posterior = (
        -(_LN_LAMBDA**2) / (2 * prior_sd**2) + m * ln_q + (n - m) * np.log(-np.expm1(ln_q))
    )
    return float(np.exp(_LN_LAMBDA[np.argmax(log_posterior)]))

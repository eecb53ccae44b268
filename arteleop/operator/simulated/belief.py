"""How sure the operator is that an error is small enough: a Gaussian belief against a criterion.

The operator believes the error is ``N(e_hat, Sigma)``: ``e_hat`` what it saw, ``Sigma`` how
precisely the cues it used let it see (it knows its precision, not its own bias). It stops
correcting once the probability that the error's length, over the axes that matter, is within
its criterion reaches its confidence; the same test says when a look has seen enough.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray
from scipy.stats import norm, qmc

_Z = norm.ppf(qmc.Sobol(3, scramble=True, seed=0).random(1024))
"""Fixed quasi-random standard normal 3-vectors (1024, 3): the probability is an average over
them, the same for the same belief in every run."""

AXES = {"xyz": (0, 1, 2), "xy": (0, 1)}
"""The axes an error is judged on: all three, or the table's plane (placement)."""


def probability_within(
    error_m: NDArray[np.float64],
    covariance_m2: NDArray[np.float64],
    criterion_m: float,
    axes: str = "xyz",
) -> float:
    """P(|e| <= criterion_m) over ``axes`` for e ~ N(error_m (3,), covariance_m2 (3, 3)),
    both in the base frame (m, m^2)."""
    keep = list(AXES[axes])
    cov = covariance_m2[np.ix_(keep, keep)]
    # Cholesky of a covariance that may be singular along an axis (a judgement without error).
    w, v = np.linalg.eigh(cov)
    root = v * np.sqrt(np.clip(w, 0.0, None))
    samples = error_m[keep] + _Z[:, : len(keep)] @ root.T
    return float(np.mean(np.einsum("ij,ij->i", samples, samples) <= criterion_m**2))


def averaging_saturated(
    first_variance_m2: float, variance_m2: float, glances: int, ratio: float = 0.1
) -> bool:
    """Whether one more glance of a look would gain nothing: the look's averaged fresh variance
    is within ``ratio`` of the variance that lasts.

    A look's believed variance after ``glances`` glances is ``L + F / glances`` (``L`` lasting:
    the person's bias where the judgement has one, a remembered offset; ``F`` one glance's fresh
    noise). The first glance's variance and the current one give both parts; a comparison of
    two points of the cloud, whose lasting error cancels, never saturates (its look ends when it
    is sure either way, or at the longest look).
    """
    if glances < 2:
        return False
    fresh = (first_variance_m2 - variance_m2) * glances / (glances - 1)
    lasting = first_variance_m2 - fresh
    return fresh / glances <= ratio * lasting

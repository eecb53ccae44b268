"""How long a movement takes: optimised submovements (Meyer, Abrams, Kornblum, Wright & Smith,
Psychological Review 1988).

A movement is a primary submovement and as many corrective ones as it takes to end within the
operator's criterion. Each submovement's endpoint scatters with a standard deviation that grows
with its mean speed, ``k * amplitude / duration`` per axis (Schmidt et al., Psychological Review
1979; signal-dependent noise, Harris & Wolpert, Nature 1998). Each one that ends outside the
criterion costs a look and a correction. The operator picks every duration to minimise the
expected time to the end: a fast primary saves time now and costs corrections later.

That trade-off is a dynamic programme over the amplitude left relative to the criterion,
``x = A / c``: ``V(x) = min_D [D + t_c + E(V(x k chi_3 / D); chi_3 > D / (x k))]`` where ``t_c``
is what one more look costs and ``chi_3`` the length of a standard normal 3-vector. With the
noise proportional to speed, ``V`` depends on ``x`` alone, so one table serves every distance and
criterion; it is solved once per look cost (rounded to ``LOOK_COST_STEP_S``) and cached. Fitts'
law is not put in: movement time grows with the index of difficulty because the optimum does.

The durations are the best that rise with ``x``: a longer movement, or a smaller tolerance, is
never given a faster submovement. People's movement times and primary submovements lengthen
with the amplitude over the tolerance (Fitts 1954; Meyer et al. 1988), whereas the unconstrained
optimum has two near-equal choices (end in one submovement, or plan on correcting) and jumps
between them: a 0.95 s primary at ``x = 40``, a 0.19 s one at ``x = 43``.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
from numpy.typing import NDArray
from scipy.stats import chi

from arteleop.operator.hand import MIN_JERK_PEAK, Submovement
from arteleop.operator.params import OperatorParams

LOOK_COST_STEP_S = 0.05
"""Resolution of the look cost's tables (s)."""
_X = np.geomspace(0.05, 2000.0, 160)  # amplitude / criterion
_D = np.geomspace(0.08, 6.0, 90)  # candidate durations (s)
_Q = chi.ppf((np.arange(48) + 0.5) / 48, 3)  # chi_3 quantiles: equal-weight quadrature


@lru_cache(maxsize=256)
def _policy(
    look_cost_s: float, noise_k_s: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(V(x), D*(x)) on ``_X`` for a look cost (s) and noise constant ``k`` (s)."""
    durations = _D[None, :]  # (1, nD)
    value = np.zeros_like(_X)
    best = np.full_like(_X, _D[0])
    log_x = np.log(_X)
    # Error left after a submovement of duration D from x: x * k / D * chi_3, as a multiple of
    # the criterion; within 1 it ends there. Fixed across the iterations: only V changes.
    left = (_X[:, None, None] * noise_k_s / durations[:, :, None]) * _Q[None, None, :]
    outside = left > 1.0
    log_left = np.log(np.maximum(left[outside], _X[0]))
    future = np.zeros_like(left)
    for _ in range(60):
        future[outside] = np.interp(log_left, log_x, value)
        expected = future.mean(axis=2)  # (nX, nD)
        total = durations + look_cost_s + expected
        choice = _rising_argmin(total)
        new = total[np.arange(len(_X)), choice]
        best = _D[choice]
        if np.max(np.abs(new - value)) < 1e-6:
            break
        value = new
    return value, best


def _rising_argmin(total: NDArray[np.float64]) -> NDArray[np.int64]:
    """Per row of ``total`` (amplitude over criterion, rising) a column (duration, rising), never
    falling from row to row, that together cost the least (summed over the rows)."""
    best_to = np.empty_like(total)  # least cost of rows 0..i with row i's choice in column j
    best_to[0] = total[0]
    for i in range(1, len(total)):
        best_to[i] = total[i] + np.minimum.accumulate(best_to[i - 1])
    choice = np.empty(len(total), dtype=np.int64)
    choice[-1] = int(np.argmin(best_to[-1]))
    for i in range(len(total) - 1, 0, -1):
        choice[i - 1] = int(np.argmin(best_to[i - 1, : choice[i] + 1]))
    return choice


def submovement_duration_s(
    amplitude_m: float, criterion_m: float, look_cost_s: float, noise_k_s: float
) -> float:
    """The duration (s) of the submovement that minimises the expected time to end within
    ``criterion_m`` from ``amplitude_m`` away, each further look costing ``look_cost_s`` and
    the endpoint's SD per axis being ``noise_k_s * amplitude / duration``."""
    cost = max(round(look_cost_s / LOOK_COST_STEP_S), 1) * LOOK_COST_STEP_S
    _, best = _policy(cost, noise_k_s)
    x = np.clip(amplitude_m / max(criterion_m, 1e-6), _X[0], _X[-1])
    return float(np.interp(np.log(x), np.log(_X), best))


def expected_time_s(
    amplitude_m: float, criterion_m: float, look_cost_s: float, noise_k_s: float
) -> float:
    """The expected time (s) from the start of a movement of ``amplitude_m`` to its end within
    ``criterion_m``, looks included, under the optimal durations."""
    cost = max(round(look_cost_s / LOOK_COST_STEP_S), 1) * LOOK_COST_STEP_S
    value, _ = _policy(cost, noise_k_s)
    x = np.clip(amplitude_m / max(criterion_m, 1e-6), _X[0], _X[-1])
    return float(np.interp(np.log(x), np.log(_X), value))


def planned_submovement(
    hand_delta_m: NDArray[np.float64],
    start_s: float,
    criterion_m: float,
    look_cost_s: float,
    params: OperatorParams,
    movement_time_factor: float,
    rng: np.random.Generator,
) -> Submovement:
    """A submovement of the hand by ``hand_delta_m`` (m) from ``start_s`` (s): its duration
    the optimal one (scaled by the person's ``movement_time_factor``, no faster than the hand's
    peak speed allows, at least 0.1 s), its endpoint scattered by its mean speed."""
    amplitude = float(np.linalg.norm(hand_delta_m))
    duration = submovement_duration_s(amplitude, criterion_m, look_cost_s, params.noise_k_s)
    duration = max(
        duration * movement_time_factor,
        MIN_JERK_PEAK * amplitude / params.peak_speed_m_s,
        0.1,
    )
    sd = params.noise_floor_m + params.noise_k_s * amplitude / duration
    return Submovement(start_s, hand_delta_m + rng.normal(0.0, sd, 3), duration, hand_delta_m, sd)

"""How long a movement takes: optimised submovements (Meyer, Abrams, Kornblum, Wright & Smith,
Psychological Review 1988).

A movement is a primary submovement and as many corrective ones as it takes to end within the
operator's criterion. Each submovement's endpoint scatters in proportion to its amplitude: along
its way by a share that falls with its duration, across it by a constant angle
(:mod:`arteleop.operator.simulated.scatter`). Each one that ends outside the criterion costs a look
and a correction. The operator picks every duration to minimise the expected time to the end: a fast
primary saves time now and costs corrections later.

That trade-off is a dynamic programme over the amplitude left relative to the criterion,
``x = A / c``: ``V(x) = min_D [D + t_c + E(V(x r(D)); x r(D) > 1)]`` where ``t_c`` is what one
more look costs and ``r(D) = sqrt(y(D)^2 z_1^2 + theta^2 (z_2^2 + z_3^2))`` the error left over
the amplitude (``y`` the share along, ``theta`` the angle across, ``z`` standard normal). With
the scatter proportional to the amplitude, ``V`` depends on ``x`` alone, so one table serves
every distance and criterion; it is solved once per look cost (rounded to ``LOOK_COST_STEP_S``)
and scatter law, and cached. Fitts' law is not put in: movement time grows with the index of
difficulty because the optimum does.

The durations are the best that never fall as ``x`` rises: a longer movement, or a smaller
tolerance, is never given a faster submovement. People's movement times and primary
submovements lengthen with the amplitude over the tolerance (Fitts 1954; Meyer et al. 1988),
whereas the unconstrained optimum has two near-equal choices (end in one submovement, or plan
on correcting) and jumps between them. With the scatter proportional to the amplitude the
optimum is flat beyond ``x`` of about 10 (0.17-0.44 s for look costs of 0.3-1.5 s): a longer
movement is slower only through the hand's peak speed (:func:`planned_submovement`).

The quadrature's 12 quantiles along the way reach 2.04 SD: below ``x y(D)`` of 0.49 it sees no
chance of ending outside the criterion where the law gives up to about 1 %.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
from numpy.typing import NDArray
from scipy.stats import chi2

from arteleop.operator.simulated.hand import MIN_JERK_PEAK, Submovement
from arteleop.operator.simulated.params import OperatorParams
from arteleop.operator.simulated.scatter import MovementScatter

LOOK_COST_STEP_S = 0.05
"""Resolution of the look cost's tables (s)."""
_X = np.geomspace(0.05, 2000.0, 160)  # amplitude / criterion
_D = np.geomspace(0.08, 6.0, 90)  # candidate durations (s)
# Equal-weight quadrature of (z_1^2, z_2^2 + z_3^2): a grid of their quantiles (independent).
_ALONG_Q, _ACROSS_Q = (
    q.ravel()
    for q in np.meshgrid(
        chi2.ppf((np.arange(12) + 0.5) / 12, 1), chi2.ppf((np.arange(12) + 0.5) / 12, 2)
    )
)


@lru_cache(maxsize=256)
def _policy(
    look_cost_s: float, scatter: MovementScatter
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(V(x), D*(x)) on ``_X`` for a look cost (s) and a scatter law."""
    durations = _D[None, :]  # (1, nD)
    value = np.zeros_like(_X)
    best = np.full_like(_X, _D[0])
    log_x = np.log(_X)
    where, log_left = _ending_outside(scatter)
    future = np.zeros((len(_X), len(_D), len(_ALONG_Q)))
    flat = future.reshape(-1)  # a view: what goes in is in ``future``
    for _ in range(60):
        flat[where] = np.interp(log_left, log_x, value)
        expected = future.mean(axis=2)  # (nX, nD)
        total = durations + look_cost_s + expected
        choice = _rising_argmin(total)
        new = total[np.arange(len(_X)), choice]
        best = _D[choice]
        if np.max(np.abs(new - value)) < 1e-6:
            break
        value = new
    return value, best


@lru_cache(maxsize=4)
def _ending_outside(scatter: MovementScatter) -> tuple[NDArray[np.intp], NDArray[np.float64]]:
    """The submovements that end outside the criterion, from each of ``_X`` with each of ``_D``
    at each of the quadrature's points (flat indices into (nX, nD, nQ)), and the log of the
    error each leaves, as a multiple of the criterion: every look cost's table iterates over
    them. In rising order of the error, in which np.interp (it looks for each point's interval
    from the last one's) finds each at once: the same values in a third to half the time."""
    left = _X[:, None, None] * _share_left(scatter)[None, :, :]
    outside = left > 1.0
    log_left = np.log(left[outside])
    order = np.argsort(log_left)
    grid = np.flatnonzero(outside)[order], log_left[order]
    for array in grid:  # shared by every table of the scatter law
        array.setflags(write=False)
    return grid


def _share_left(scatter: MovementScatter) -> NDArray[np.float64]:
    """The error a submovement of each of ``_D`` leaves, over its amplitude, at each of the
    quadrature's points (nD, nQ)."""
    along = scatter.along_share(_D)[:, None] ** 2 * _ALONG_Q[None, :]
    return np.sqrt(along + scatter.direction_sd_rad**2 * _ACROSS_Q[None, :])


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
    amplitude_m: float, criterion_m: float, look_cost_s: float, scatter: MovementScatter
) -> float:
    """The duration (s) of the submovement that minimises the expected time to end within
    ``criterion_m`` from ``amplitude_m`` away, each further look costing ``look_cost_s`` and
    the endpoint scattering by ``scatter``."""
    cost = max(round(look_cost_s / LOOK_COST_STEP_S), 1) * LOOK_COST_STEP_S
    _, best = _policy(cost, scatter)
    x = np.clip(amplitude_m / max(criterion_m, 1e-6), _X[0], _X[-1])
    return float(np.interp(np.log(x), np.log(_X), best))


def expected_time_s(
    amplitude_m: float, criterion_m: float, look_cost_s: float, scatter: MovementScatter
) -> float:
    """The expected time (s) from the start of a movement of ``amplitude_m`` to its end within
    ``criterion_m``, looks included, under the optimal durations."""
    cost = max(round(look_cost_s / LOOK_COST_STEP_S), 1) * LOOK_COST_STEP_S
    value, _ = _policy(cost, scatter)
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
    peak speed allows, at least 0.1 s), its endpoint scattered along and across its way by
    that duration."""
    amplitude = float(np.linalg.norm(hand_delta_m))
    duration = submovement_duration_s(amplitude, criterion_m, look_cost_s, params.scatter)
    duration = max(
        duration * movement_time_factor,
        MIN_JERK_PEAK * amplitude / params.peak_speed_m_s,
        0.1,
    )
    end = hand_delta_m + params.scatter.endpoint_error_m(hand_delta_m, duration, rng)
    cov = params.scatter.covariance_m2(hand_delta_m, duration)
    return Submovement(start_s, end, duration, hand_delta_m, cov)

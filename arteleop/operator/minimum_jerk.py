"""Minimum-jerk point-to-point movements (Flash & Hogan, J. Neurosci. 1985)."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from arteleop.errors import ConfigurationError


def minimum_jerk_profile(tau: ArrayLike) -> NDArray[np.float64]:
    """Normalised position 10 tau^3 - 15 tau^4 + 6 tau^5 at normalised time tau in [0, 1]."""
    t = np.clip(np.asarray(tau, dtype=np.float64), 0.0, 1.0)
    return t**3 * (10.0 - 15.0 * t + 6.0 * t**2)


def minimum_jerk(
    start_m: ArrayLike, end_m: ArrayLike, duration_s: float, time_s: ArrayLike
) -> NDArray[np.float64]:
    """Positions (len(time_s), D) of a minimum-jerk movement from ``start_m`` to ``end_m``.

    The movement starts at t = 0 and rests at ``end_m`` after ``duration_s``.
    """
    if not duration_s > 0:
        raise ConfigurationError(f"movement duration must be > 0 s, got {duration_s}")
    a, b = np.asarray(start_m, dtype=np.float64), np.asarray(end_m, dtype=np.float64)
    s = minimum_jerk_profile(np.asarray(time_s, dtype=np.float64) / duration_s)
    return a + np.multiply.outer(s, b - a)

"""The operator's hand speed, robust to the wearable's orientation noise."""

from __future__ import annotations

from collections import deque

import numpy as np
from numpy.typing import ArrayLike, NDArray

from arteleop.errors import ConfigurationError


class HandSpeed:
    """Speed (m/s) as the slope of a straight line fitted to the positions of the last
    ``window_s`` seconds.

    Sample-to-sample differences won't do: with the wearable's default errors (1 deg of wandering
    orientation error per sensor) the reconstructed hand of a still arm moves 1.5-2.5 mm between
    10 ms samples, which reads as 0.15-0.25 m/s. A least-squares slope over 0.3 s reads under
    0.03 m/s (tests/teleop/test_hand_speed.py).
    """

    def __init__(self, window_s: float = 0.3) -> None:
        if window_s <= 0:
            raise ConfigurationError(f"the hand-speed window must be > 0 s, got {window_s}")
        self.window_s = window_s
        self.speed_m_s = 0.0
        self._recent: deque[tuple[float, NDArray[np.float64]]] = deque()

    def update(self, time_s: float, position_m: ArrayLike) -> float:
        """Add a position (m) at ``time_s`` (s, increasing) and return the current speed."""
        recent = self._recent
        recent.append((time_s, np.asarray(position_m, dtype=np.float64)))
        while recent[0][0] < time_s - self.window_s:
            recent.popleft()
        if len(recent) >= 3:
            t = np.array([r[0] for r in recent])
            p = np.array([r[1] for r in recent])
            t -= t.mean()
            slope = (t @ (p - p.mean(axis=0))) / (t @ t)
            self.speed_m_s = float(np.linalg.norm(slope))
        return self.speed_m_s

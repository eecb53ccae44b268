"""End-to-end latency (docs/explanation/study.md §7, for the whole loop): from an operator sample
to the first display frame that shows it.

- Simulated: at each camera frame's capture, its time minus the newest sample acting on the arm
  (network, control and camera rates).
- Wall clock (real time only): from the sample's creation to the moment the frame that first
  shows it is on the display.
"""

from __future__ import annotations

import time
from collections import deque

import numpy as np
from numpy.typing import NDArray


class LatencyAccount:
    """Collects both latencies over a trial."""

    def __init__(self) -> None:
        self._sim_s: list[float] = []
        self._wall_s: list[float] = []
        self._created: deque[tuple[float, float]] = deque()  # (sample time, wall clock)

    def sample_created(self, sample_time_s: float, wall_s: float) -> None:
        """Real time: the operator produced a sample at wall-clock ``wall_s``."""
        self._created.append((sample_time_s, wall_s))

    def frame_captured(self, t: float, applied_sample_time_s: float) -> None:
        """A camera frame captured at ``t`` shows the samples up to ``applied_sample_time_s``."""
        if np.isfinite(applied_sample_time_s):
            self._sim_s.append(t - applied_sample_time_s)

    def frame_shown(self, applied_sample_time_s: float) -> None:
        """A frame showing the samples up to ``applied_sample_time_s`` is on the display now."""
        created = self._created
        while len(created) > 1 and created[1][0] <= applied_sample_time_s:
            created.popleft()
        if created and created[0][0] == applied_sample_time_s:
            self._wall_s.append(time.perf_counter() - created[0][1])

    @property
    def sim_ms(self) -> NDArray[np.float64]:
        return np.array(self._sim_s) * 1000

    @property
    def wall_ms(self) -> NDArray[np.float64]:
        return np.array(self._wall_s) * 1000

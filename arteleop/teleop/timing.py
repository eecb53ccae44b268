"""Per-stage performance figures (docs/explanation/study.md §7): service time and latency.

- Service time: wall-clock time between two completed rounds of a stage.
- Latency: time from a stage's input to its output. For a stage that computes, the compute time;
  for the whole loop, from an operator sample to its first visible effect.
"""

from __future__ import annotations

import time
from collections import defaultdict
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class StageStats:
    """Summary of one stage (milliseconds)."""

    stage: str
    rounds: int
    service_median_ms: float
    service_p95_ms: float
    latency_median_ms: float
    latency_p95_ms: float
    latency_p99_ms: float
    latency_total_ms: float
    """Wall time spent in the stage over the whole run."""


class _Round:
    """One timed round of a stage: a plain class, as a generator-based context manager costs
    a few microseconds more on the 240 Hz physics path."""

    __slots__ = ("_stage", "_start", "_timer")

    def __init__(self, timer: StageTimer, stage: str) -> None:
        self._timer, self._stage = timer, stage

    def __enter__(self) -> None:
        self._start = time.perf_counter()

    def __exit__(self, *exc: object) -> None:
        self._timer.record(self._stage, self._start)


class StageTimer:
    """Collects service times and latencies per stage."""

    def __init__(self) -> None:
        self._last_end: dict[str, float] = {}
        self._service: dict[str, list[float]] = defaultdict(list)
        self._latency: dict[str, list[float]] = defaultdict(list)

    def record(self, stage: str, start_s: float, end_s: float | None = None) -> None:
        """A round of ``stage`` ran from ``start_s`` to ``end_s`` (default: now), wall clock."""
        end = time.perf_counter() if end_s is None else end_s
        if stage in self._last_end:
            self._service[stage].append(end - self._last_end[stage])
        self._last_end[stage] = end
        self._latency[stage].append(end - start_s)

    def stage(self, stage: str) -> _Round:
        """Time the ``with`` block as one round of ``stage``."""
        return _Round(self, stage)

    def summary(self) -> list[StageStats]:
        rows = []
        for stage in self._latency:
            s = np.asarray(self._service.get(stage, [np.nan])) * 1000
            lat = np.asarray(self._latency[stage]) * 1000
            rows.append(StageStats(
                stage, len(lat), float(np.median(s)), float(np.percentile(s, 95)),
                float(np.median(lat)), float(np.percentile(lat, 95)), float(np.percentile(lat, 99)),
                float(lat.sum()),
            ))  # fmt: skip
        return rows

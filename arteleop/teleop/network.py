"""The link between operator and robot: one-way delay, jitter and packet loss.

Packets carry the time their sample was taken. The receiver hands over only packets newer than
the newest it has delivered: a late packet never makes the robot move backwards in time.
"""

from __future__ import annotations

import heapq
from dataclasses import dataclass, field
from typing import Generic, TypeVar

import numpy as np

from arteleop.errors import ConfigurationError

T = TypeVar("T")


@dataclass(frozen=True)
class NetworkConfig:
    """Link properties.

    Attributes:
        delay_s: Mean one-way delay (s).
        jitter_s: Standard deviation of the delay (s); delays never go below zero.
        loss_probability: Chance that a packet is lost.
    """

    delay_s: float = 0.0
    jitter_s: float = 0.0
    loss_probability: float = 0.0

    def __post_init__(self) -> None:
        if self.delay_s < 0 or self.jitter_s < 0 or not 0 <= self.loss_probability < 1:
            raise ConfigurationError(
                f"NetworkConfig: delay_s ({self.delay_s}) and jitter_s ({self.jitter_s}) must be "
                f">= 0 and loss_probability ({self.loss_probability}) in [0, 1)"
            )


@dataclass(order=True)
class _InFlight(Generic[T]):
    arrival_s: float
    seq: int
    sample_time_s: float = field(compare=False)
    payload: T = field(compare=False)


class NetworkLink(Generic[T]):
    """A one-way link that delivers payloads stamped with their sample time."""

    def __init__(self, config: NetworkConfig, rng: np.random.Generator) -> None:
        self.config = config
        self._rng = rng
        self._queue: list[_InFlight[T]] = []
        self._seq = 0
        self._newest = -np.inf
        self.sent = self.lost = self.late = 0

    def send(self, sample_time_s: float, payload: T, now_s: float) -> None:
        """Put a packet on the wire at ``now_s``."""
        self.sent += 1
        if self.config.loss_probability and self._rng.random() < self.config.loss_probability:
            self.lost += 1
            return
        delay = self.config.delay_s
        if self.config.jitter_s:
            delay = max(0.0, delay + self._rng.normal(0.0, self.config.jitter_s))
        self._seq += 1
        heapq.heappush(self._queue, _InFlight(now_s + delay, self._seq, sample_time_s, payload))

    def receive(self, now_s: float) -> list[tuple[float, T]]:
        """(sample time, payload) of the packets arrived by ``now_s``, oldest sample first."""
        out = []
        while self._queue and self._queue[0].arrival_s <= now_s:
            packet = heapq.heappop(self._queue)
            if packet.sample_time_s <= self._newest:
                self.late += 1  # overtaken by a newer sample: dropped, never applied
                continue
            self._newest = packet.sample_time_s
            out.append((packet.sample_time_s, packet.payload))
        return out

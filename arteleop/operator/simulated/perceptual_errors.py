"""A person's judgement errors: a lasting bias per judgement, and fresh noise at each glance that
a longer look averages."""

from __future__ import annotations

import zlib

import numpy as np
from numpy.typing import NDArray


class PerceptualErrors:
    """A person's judgement errors in standard units, one stream per judgement.

    A stream's bias is drawn once from ``bias_seed`` and the stream's name, so a person errs the
    same way in every trial; each glance adds fresh noise from ``rng``, averaged over the look's
    glances (:meth:`new_look` starts a look).
    """

    def __init__(self, rng: np.random.Generator, bias_seed: int, bias_share: float) -> None:
        self._rng = rng
        self._seed = bias_seed
        self._bias_sd, self._fresh_sd = np.sqrt(bias_share), np.sqrt(1.0 - bias_share)
        self._bias: dict[str, NDArray[np.float64]] = {}
        self._sums: dict[str, tuple[int, NDArray[np.float64]]] = {}

    def new_look(self) -> None:
        """Forget the fresh noise of the last look."""
        self._sums.clear()

    def draw(self, stream: str, size: int) -> NDArray[np.float64]:
        """One more glance at ``stream``: the bias plus the mean of this look's fresh noise,
        weighted by the split of a glance's variance."""
        fresh = self.draw_fresh(stream, size)
        return self._bias_sd * self.bias(stream, size) + self._fresh_sd * fresh

    def draw_fresh(self, stream: str, size: int) -> NDArray[np.float64]:
        """One more glance at ``stream`` without a lasting part: the mean of this look's
        fresh noise (standard units per glance)."""
        n, total = self._sums.get(stream, (0, np.zeros(size)))
        n, total = n + 1, total + self._rng.normal(0.0, 1.0, size)
        self._sums[stream] = (n, total)
        return total / n

    def drift(self, size: int) -> NDArray[np.float64]:
        """Standard normal steps of a memory's drift: fresh, never averaged over a look."""
        return self._rng.normal(0.0, 1.0, size)

    def bias(self, stream: str, size: int) -> NDArray[np.float64]:
        """The person's lasting bias of ``stream`` (standard units)."""
        bias = self._bias.get(stream)
        if bias is None:
            stream_rng = np.random.default_rng([self._seed, zlib.crc32(stream.encode())])
            bias = self._bias[stream] = stream_rng.normal(0.0, 1.0, size)
        return bias

    def glances(self, stream: str) -> int:
        """Glances at ``stream`` in this look."""
        return self._sums.get(stream, (0, None))[0]

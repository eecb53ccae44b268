"""One clock for the whole loop: control, physics and camera ticks at their own rates.

Time advances in base ticks at the least common multiple of the rates (1200 Hz for 100, 240 and
30 Hz), so every stage fires at exact multiples of its period and the event order never depends
on floating-point rounding. In batch mode the loop runs as fast as it can; in real-time mode it
sleeps so that simulated time keeps pace with the wall clock. The sequence of events is the same
in both, hence the same robot motion for the same inputs and seed.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

from arteleop.errors import ConfigurationError


@dataclass(frozen=True)
class LoopRates:
    """Rates of the loop's stages (Hz, whole numbers).

    ``tracking_hz`` is the bowl tracker's: its estimate is updated every
    :attr:`frames_per_track` camera frames and held in between, as a tracker slower than the
    camera.
    """

    control_hz: int = 100
    physics_hz: int = 240
    camera_hz: int = 30
    tracking_hz: int = 10

    def __post_init__(self) -> None:
        for name in ("control_hz", "physics_hz", "camera_hz", "tracking_hz"):
            value = getattr(self, name)
            if not isinstance(value, int) or value <= 0:
                raise ConfigurationError(
                    f"LoopRates.{name} must be a positive whole number, got {value}"
                )
        if self.physics_hz < 240:
            raise ConfigurationError(f"physics_hz={self.physics_hz}: use at least 240 Hz")
        if self.tracking_hz > self.camera_hz:
            raise ConfigurationError(
                f"tracking_hz={self.tracking_hz} exceeds camera_hz={self.camera_hz}: the tracker "
                "runs on camera frames"
            )

    @property
    def frames_per_track(self) -> int:
        """Camera frames per tracker update: the nearest whole number to the rates' ratio."""
        return max(1, round(self.camera_hz / self.tracking_hz))

    @property
    def base_hz(self) -> int:
        return math.lcm(self.control_hz, self.physics_hz, self.camera_hz)


@dataclass(frozen=True)
class Tick:
    """What fires at one base tick."""

    index: int
    time_s: float
    control: bool
    physics: bool
    camera: bool


class LoopClock:
    """Yields ticks; in real time, waits for the wall clock before each one.

    Args:
        rates: The stages' rates.
        realtime: Keep pace with the wall clock.
        idle_ticks: Also yield the base ticks at which no stage fires (most of them: 880 of
            1200 a second at the default rates), at which a real-time loop polls its render
            process and delivers frames. False skips them, for a loop with nothing to do
            between its stages.
        stop_s: Without idle ticks, the first base tick after this time (s) is yielded all the
            same, so that a loop that stops there (its timeout) stops at the same instant.
    """

    def __init__(
        self,
        rates: LoopRates,
        realtime: bool = False,
        idle_ticks: bool = True,
        stop_s: float = math.inf,
    ) -> None:
        self.rates = rates
        self.realtime = realtime
        base = rates.base_hz
        self._every = (base // rates.control_hz, base // rates.physics_hz, base // rates.camera_hz)
        self._base = base
        self._k = 0
        self._wall0: float | None = None
        self._idle = idle_ticks
        self._stop_k = math.inf
        if math.isfinite(stop_s):
            k = max(0, math.floor(stop_s * base))
            while k / base <= stop_s:
                k += 1
            self._stop_k = k

    def next(self) -> Tick:
        k = self._k
        if not self._idle:
            c, p, cam = self._every
            k = min((k + c - 1) // c * c, (k + p - 1) // p * p, (k + cam - 1) // cam * cam)
            if self._k <= self._stop_k < k:
                k = self._stop_k
        self._k = k + 1
        t = k / self._base
        if self.realtime:
            if self._wall0 is None:
                self._wall0 = time.perf_counter()
            delay = self._wall0 + t - time.perf_counter()
            if delay > 0:
                time.sleep(delay)
        c, p, cam = (k % e == 0 for e in self._every)
        return Tick(k, t, c, p, cam)

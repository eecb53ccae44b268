"""The robot side's filter of the operator's hand: a 1€ filter on the reconstructed pose.

A wearable's orientation noise reaches the reconstructed hand as millimetres of jitter at rest,
which position control would pass on to the gripper. Real teleoperation systems filter the hand
they receive; the 1€ filter (Casiez, Roussel & Vogel, CHI 2012) is the standard for jittery
trackers: a first-order low-pass filter whose cutoff rises with the signal's speed, so a still
hand is smoothed hard and a moving one is followed with little lag. The authors' own Python
implementation (PyPI ``OneEuroFilter``) filters each coordinate.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from OneEuroFilter import OneEuroFilter

from arteleop.checks import Bounds, check_fields


@dataclass(frozen=True)
class HandFilterConfig:
    """The 1€ filter's parameters, the same for each coordinate of the hand's position (m) and
    of its orientation quaternion.

    Tuned as Casiez et al. advise (``benchmarks/bench_hand_filter.py`` prints the numbers):
    the minimum cutoff for jitter with the hand at rest, then ``beta`` for lag in fast motion.

    Attributes:
        enabled: Filter the hand; False sends the reconstructed hand to the mapping as it is.
        min_cutoff_hz: Cutoff at rest (Hz): lower removes more jitter and adds more lag.
        beta_per_m: How fast the cutoff rises with the hand's speed (Hz of cutoff per m/s).
        derivative_cutoff_hz: Cutoff of the speed estimate that drives the cutoff (Hz); the
            paper's 1 Hz.
    """

    enabled: bool = True
    min_cutoff_hz: float = 1.0
    beta_per_m: float = 5.0
    derivative_cutoff_hz: float = 1.0

    def __post_init__(self) -> None:
        cutoff = Bounds(0.01, 100.0, text="a cutoff of 0.01-100 Hz")
        check_fields(self, {
            "min_cutoff_hz": cutoff,
            "derivative_cutoff_hz": cutoff,
            "beta_per_m": Bounds(0.0, 1000.0,
                                 text="0-1000 (Hz per m/s; 0 is a plain low-pass filter)"),
        })  # fmt: skip


class HandFilter:
    """Filters one hand pose after another: position (m) and orientation (w, x, y, z)."""

    def __init__(self, config: HandFilterConfig, rate_hz: float) -> None:
        """``rate_hz``: the samples' nominal rate; the filter follows their timestamps."""
        c = config
        self.config = config
        self._filters = [
            OneEuroFilter(rate_hz, c.min_cutoff_hz, c.beta_per_m, c.derivative_cutoff_hz)
            for _ in range(7)
        ]
        self._last_quat: NDArray[np.float64] | None = None

    def __call__(
        self, time_s: float, hand_m: NDArray[np.float64], quat_wxyz: NDArray[np.float64]
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """The filtered (position, unit quaternion) of the hand sampled at ``time_s`` (s)."""
        if not self.config.enabled:
            return hand_m, quat_wxyz
        # q and -q are one rotation: keep the sign nearest the last one, so the filter never
        # averages across the sign flip.
        q = quat_wxyz if self._last_quat is None or quat_wxyz @ self._last_quat >= 0 else -quat_wxyz
        self._last_quat = q
        # The filter skips its rate update on a timestamp of 0 (falsy): start just after it.
        stamp = time_s + 1e-9
        out = np.array(
            [f(float(v), stamp) for f, v in zip(self._filters, (*hand_m, *q), strict=True)]
        )
        quat = out[3:] / np.linalg.norm(out[3:])
        return out[:3], quat


def filter_hand_path(
    config: HandFilterConfig,
    time_s: NDArray[np.float64],
    hand_m: NDArray[np.float64],
    quat_wxyz: NDArray[np.float64],
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """A whole reconstructed path (N,), (N, 3), (N, 4) through a fresh filter, sample by sample,
    as the controller would see it: filtered positions (N, 3) and orientations (N, 4)."""
    rate = 1.0 / float(np.median(np.diff(time_s))) if len(time_s) > 1 else 100.0
    f = HandFilter(config, rate)
    out = [f(float(t), p, q) for t, p, q in zip(time_s, hand_m, quat_wxyz, strict=True)]
    return np.array([p for p, _ in out]), np.array([q for _, q in out])

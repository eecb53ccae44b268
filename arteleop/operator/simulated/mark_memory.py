"""Where the operator remembers a mark on the table that the display no longer draws.

A mark (the target circle, the start cross) is judged only where the point cloud draws enough of
it (``DisplayFrame.target_drawn``, ``start_drawn``). Hidden by the arm or the bowl, it is placed
from memory: where it was last judged, and the longer it has been unseen the further memory has
drifted from there. Memory-guided saccades and reaches err more the longer the delay (White,
Sparks & Stanford 1994, to 5.6 s; Westwood, Heath & Roy 2003) up to about 20 s, beyond which the
error no longer grows (Ploner et al. 1998): a drift whose variance grows in proportion to the
time unseen, up to that plateau. The person knows that memory fades: the drift's variance is in
the remembered mark's believed covariance, not the drift itself.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from arteleop.operator.simulated.perceptual_errors import PerceptualErrors

if TYPE_CHECKING:
    from arteleop.operator.simulated.perception import PerceptionParams


@dataclass
class _Remembered:
    mark_m: NDArray[np.float64]
    cov: NDArray[np.float64]
    seen_s: float
    drift_m: NDArray[np.float64]
    drifted_to_s: float


class MarkMemory:
    """The marks last seen, each with the drift of its memory since: by ``params``'
    ``memory_drift_rad`` (the SD per axis in the table's plane, as an angle at the eye, that a
    mark's remembered place drifts by in its first second unseen, rad) up to its
    ``memory_plateau_s`` (how long the drift grows, s)."""

    def __init__(self, params: PerceptionParams) -> None:
        self._drift_rad = params.memory_drift_rad
        self._plateau_s = params.memory_plateau_s
        self._marks: dict[str, _Remembered] = {}

    def saw(
        self, name: str, time_s: float, mark_m: NDArray[np.float64], cov: NDArray[np.float64]
    ) -> None:
        """The mark ``name`` was judged at ``mark_m`` (base frame, m) with believed covariance
        ``cov`` (m^2) in the frame captured at ``time_s`` (s)."""
        self._marks[name] = _Remembered(mark_m.copy(), cov.copy(), time_s, np.zeros(3), time_s)

    def recall(
        self,
        name: str,
        time_s: float,
        viewpoint_m: NDArray[np.float64],
        errors: PerceptualErrors,
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]] | None:
        """Where the mark ``name`` is remembered at ``time_s`` (s), seen from ``viewpoint_m``
        (m), and the covariance believed (m^2); None if it was never seen. The drift since the
        last recall is drawn from ``errors``, fresh: memory is not averaged by looking."""
        mark = self._marks.get(name)
        if mark is None:
            return None
        until_s = min(time_s, mark.seen_s + self._plateau_s)
        sd_m = self._drift_rad * float(np.linalg.norm(mark.mark_m - viewpoint_m))
        if until_s > mark.drifted_to_s:
            step_sd = sd_m * math.sqrt(until_s - mark.drifted_to_s)
            mark.drift_m[:2] += errors.drift(2) * step_sd
            mark.drifted_to_s = until_s
        unseen_var = sd_m**2 * (mark.drifted_to_s - mark.seen_s)
        return mark.mark_m + mark.drift_m, mark.cov + np.diag([unseen_var, unseen_var, 0.0])

"""Where a submovement's endpoint scatters: along its way with its duration, across it by a
constant angle.

Along the movement the scatter relative to the amplitude, ``y = SD / A``, falls with the
movement time ``x`` (s) as Guiard & Rioul (British HCI 2015) fit people's aiming:
``(y - y0)^(1 - alpha) (x - x0)^alpha = k^alpha``, with their fit of Guiard, Olafsdottir &
Perrault's (2011) 15 cm stylus movements under five speed-accuracy instructions (movement
times 0.69-2.06 s). Those movements had visual feedback; a primary submovement, whose
corrections the operator makes itself, scatters at least this much. Faster than the fit's
data, the scatter grows with the mean speed, ``y ∝ 1 / x`` at a given amplitude (Schmidt,
Zelaznik, Hawkins, Frank & Quinn, Psychol. Rev. 1979), joined to the fit where its data begin:
the fit's own pole at ``x0`` is no movement's.

Across the movement the scatter is a constant angle (Gordon, Ghilardi & Ghez, Exp. Brain Res.
99, 1994: directional variability in angular terms is constant, the endpoint ellipses long
along the movement). With the amplitude fixed, only the scatter along grows with speed.

Both are proportional to the amplitude, so the submovement planner's table depends on the
amplitude over the criterion alone.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from arteleop.checks import Bounds, check_fields


@dataclass(frozen=True)
class MovementScatter:
    """A submovement's endpoint scatter (docs/explanation/operator-model.md gives each value's
    source).

    Attributes:
        alpha: Guiard & Rioul's exponent (the trade-off's shape).
        k: Their constant (relative scatter and seconds).
        x0_s: The movement time their fit's scatter tends to infinity at (s).
        y0: The relative scatter of the slowest movements (SD over the amplitude).
        fit_from_s: The shortest movement time of the fit's data (s); faster, the scatter
            grows with the mean speed.
        direction_sd_rad: SD of the movement's direction (rad): the scatter across its way,
            per axis, over the amplitude.
    """

    alpha: float = 0.60
    k: float = 0.070
    x0_s: float = 0.092
    y0: float = 0.0018
    fit_from_s: float = 0.69
    direction_sd_rad: float = 0.026

    def __post_init__(self) -> None:
        check_fields(self, {
            "alpha": Bounds(0, 0.95, "an exponent", above=True),
            "k": Bounds(0, above=True),
            "x0_s": Bounds(0),
            "y0": Bounds(0),
            "direction_sd_rad": Bounds(0, 0.5, "rad"),
        })  # fmt: skip
        # The fit's pole must lie below where it is used.
        check_fields(self, {"fit_from_s": Bounds(self.x0_s, 10.0, "s", above=True)})

    def along_share(self, duration_s: NDArray[np.float64] | float) -> NDArray[np.float64]:
        """The endpoint's SD along the movement over its amplitude, for a movement of
        ``duration_s`` (s)."""
        x = np.asarray(duration_s, dtype=float)
        power = self.alpha / (1.0 - self.alpha)
        fitted = self.y0 + self.k**power * np.maximum(x - self.x0_s, 1e-9) ** -power
        at_edge = self.y0 + self.k**power * (self.fit_from_s - self.x0_s) ** -power
        return np.where(x >= self.fit_from_s, fitted, at_edge * self.fit_from_s / x)

    def covariance_m2(self, delta_m: NDArray[np.float64], duration_s: float) -> NDArray[np.float64]:
        """The endpoint's covariance (m^2) of a movement by ``delta_m`` (m) over
        ``duration_s`` (s): along ``delta_m`` and across it."""
        along, across, way = self._parts(delta_m, duration_s)
        return across**2 * np.eye(3) + (along**2 - across**2) * np.outer(way, way)

    def endpoint_error_m(
        self, delta_m: NDArray[np.float64], duration_s: float, rng: np.random.Generator
    ) -> NDArray[np.float64]:
        """A draw (m) of where a movement by ``delta_m`` (m) over ``duration_s`` (s) ends,
        about ``delta_m``: of :meth:`covariance_m2`."""
        along, across, way = self._parts(delta_m, duration_s)
        z = rng.normal(0.0, 1.0, 3)
        return across * z + (along - across) * float(way @ z) * way

    def _parts(
        self, delta_m: NDArray[np.float64], duration_s: float
    ) -> tuple[float, float, NDArray[np.float64]]:
        """The SDs (m) along and across the way, and the way (a unit vector)."""
        amplitude = float(np.linalg.norm(delta_m))
        if amplitude == 0.0:
            return 0.0, 0.0, np.zeros(3)
        along = amplitude * float(self.along_share(duration_s))
        return along, amplitude * self.direction_sd_rad, np.asarray(delta_m) / amplitude

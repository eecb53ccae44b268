"""How precisely a person judges what a display draws: one function of the display's geometry and
published acuities, for every judgement of every layer (docs/explanation/operator-model.md gives
each value's source).

A judgement is of where one drawn thing is relative to another (the gripper against the grasp
point, the bowl against the target mesh, the centre of a circle against its rim). Its precision
across the line of sight has two parts:

- the **interval** judged: the precision of a spatial interval is a fixed fraction of it
  (Weber's law for spatial intervals), so a far goal is judged coarsely and a near one finely;
- the **grain** the two things are drawn at: the coarser of the display's pixel and the point
  cloud's spacing, seen at the viewing distance; a position within a grain is unknown (a
  uniform error, SD grain / sqrt(12)).

Along the line of sight the display's stereo disparity gives depth: a disparity error ``d``
(rad) at viewing distance ``z`` is a depth error ``z**2 d / interocular``, and the interval's
Weber part applies as across it. A number drawn as a label is read to its last digit.

A judgement takes as many fixations as what it combines needs (:func:`fixations`): a label is
read only in the fovea; where a thing is, is seen anywhere in the parafovea around a fixation;
whatever no fixation covers needs the eyes to move.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from arteleop.checks import Bounds, check_fields

ARCMIN_RAD = math.pi / (180 * 60)
"""One minute of arc (rad)."""


@dataclass(frozen=True)
class DisplayGeometry:
    """The display the operator looks through, as the eye sees it.

    Attributes:
        pixel_rad: The angle one of the display's pixels subtends at the eye (rad). The
            original study's Oculus Rift DK2: 960 px across 83 deg per eye.
        interocular_m: The distance between the eyes the stereo rendering uses (m).
    """

    pixel_rad: float = math.radians(83.0) / 960
    interocular_m: float = 0.063

    def __post_init__(self) -> None:
        check_fields(self, {
            "pixel_rad": Bounds(0.0, 0.02, "rad"),
            "interocular_m": Bounds(0.04, 0.08, "m"),
        })  # fmt: skip


@dataclass(frozen=True)
class Acuities:
    """Published acuities of a viewer with normal vision (one glance's SDs).

    Attributes:
        interval_fraction: SD of a judged spatial interval as a fraction of the interval.
        stereo_pixels: SD of a disparity judged in a head-mounted display, in the display's
            pixels (stereo acuity in HMDs is a fixed share of a pixel).
    """

    interval_fraction: float = 0.03
    stereo_pixels: float = 1 / 6.3

    def __post_init__(self) -> None:
        check_fields(self, {
            "interval_fraction": Bounds(0.0, 0.5, "a fraction of the interval"),
            "stereo_pixels": Bounds(0.0, 5.0, "display pixels"),
        })  # fmt: skip


@dataclass(frozen=True)
class Judgement:
    """One glance's precision of a drawn thing's position relative to another (m): ``across``
    the line of sight (per axis) and ``depth`` along it."""

    across_sd_m: float
    depth_sd_m: float


def judgement_sd(
    interval_m: float,
    viewing_distance_m: float,
    grain_rad: float,
    display: DisplayGeometry,
    acuities: Acuities,
) -> Judgement:
    """The precision of judging a drawn thing ``interval_m`` from its reference, both seen at
    ``viewing_distance_m`` and drawn at ``grain_rad`` (the coarser of the display's pixel and
    the cloud's spacing; never finer than the display's pixel)."""
    grain_rad = max(grain_rad, display.pixel_rad)
    weber = acuities.interval_fraction * interval_m
    across = math.hypot(weber, viewing_distance_m * grain_rad / math.sqrt(12))
    disparity_rad = acuities.stereo_pixels * display.pixel_rad
    stereo = viewing_distance_m**2 * disparity_rad / display.interocular_m
    return Judgement(across, math.hypot(weber, stereo))


def reading_sd_m(step_m: float) -> float:
    """The precision of a value read off a label that shows it to ``step_m`` (m): rounding's."""
    return step_m / math.sqrt(12)


def fixations(
    seen_m: Sequence[NDArray[np.float64]],
    read_m: Sequence[NDArray[np.float64]],
    viewpoint_m: NDArray[np.float64],
    parafovea_rad: float,
    fovea_rad: float,
) -> int:
    """How many fixations it takes, from ``viewpoint_m``, to read the labels at ``read_m`` (each
    must be within ``fovea_rad`` of a fixation) and to see where the things at ``seen_m`` are
    (within ``parafovea_rad`` of one); base frame, m. Labels are fixated first, things are
    fixated in order where no fixation covers them. At least one: a judgement looks somewhere."""
    fixated: list[NDArray[np.float64]] = []

    def fixate(points: Sequence[NDArray[np.float64]], span_rad: float) -> None:
        covered = math.cos(span_rad)  # rays closer than the span have a larger cosine
        for point in points:
            ray = point - viewpoint_m
            ray = ray / np.linalg.norm(ray)
            if all(float(ray @ f) < covered for f in fixated):
                fixated.append(ray)

    fixate(read_m, fovea_rad)
    fixate(seen_m, parafovea_rad)
    return max(len(fixated), 1)

"""A pointing study's design (the study file's ``[pointing]`` table, with ``task = "pointing"``):
the targets' distances and widths, how often each cell comes, and the order a person meets them.

The lags are the study's ``[[conditions]]``, a network profile each, met in blocks: a person does
every cell ``repetitions`` times under one lag, then under the next, as MacKenzie & Ware (CHI
1993) ran theirs. Within a block each repetition's cells come in an order shuffled for the person
and the repetition, the same at every lag, and so do the trials' seeds: the lags are compared on
the same trials (docs/explanation/operator-model.md, the calibration task).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from arteleop.errors import StudyDefinitionError

MOST_CELL_VALUES = 9
"""Distances, and widths, at most: a trial's seed gives each cell a decimal digit."""
MOST_REPETITIONS = 99
"""Repetitions of a cell at most: a trial's seed gives them two decimal digits."""
MOST_PEOPLE = 999
"""Participants of a pointing study at most: a trial's seed gives them 10000 seeds each."""
LONGEST_TIMEOUT_S = 600.0
"""A pointing trial's timeout at most (s): a pointing movement takes seconds."""
DISTANCE_RANGE_M = (0.02, 0.4)
"""A target's distance from the start (m): from a hand's width to what the arm reaches from the
pointing start over the table."""
WIDTH_RANGE_M = (0.005, 0.1)
"""A target's diameter (m): from what the head camera's cloud still resolves at the table (about
4 mm a point) to the bowl's size."""


@dataclass(frozen=True)
class PointingTrial:
    """One planned pointing trial.

    Attributes:
        distance_m: From the start cross to the target's centre, along +y (m).
        width_m: The target circle's diameter (m).
        rep: The repetition of its cell, from 0.
        seed: The trial's seed.
    """

    distance_m: float
    width_m: float
    rep: int
    seed: int


@dataclass(frozen=True)
class PointingDesign:
    """The cells of a pointing study and their repetitions.

    Attributes:
        distances_m: The targets' distances from the start (m), each 0.02-0.4, at most 9.
        widths_m: The targets' diameters (m), each 0.005-0.1 and less than the shortest
            distance, at most 9.
        repetitions: Trials of each cell under each lag, 2-99: the effective width needs a
            spread.
        timeout_s: Simulated time after which a trial with no selection ends (s).
    """

    distances_m: tuple[float, ...] = (0.1, 0.2, 0.4)
    widths_m: tuple[float, ...] = (0.01, 0.02, 0.04)
    repetitions: int = 5
    timeout_s: float = 40.0

    def __post_init__(self) -> None:
        for key, values, (low, high) in (("distances_m", self.distances_m, DISTANCE_RANGE_M),
                                         ("widths_m", self.widths_m, WIDTH_RANGE_M)):  # fmt: skip
            if not (
                1 <= len(values) <= MOST_CELL_VALUES
                and all(math.isfinite(v) and low <= v <= high for v in values)
                and len(set(values)) == len(values)
            ):
                raise StudyDefinitionError(
                    f"pointing.{key} = {list(values)}: expected 1 to {MOST_CELL_VALUES} different "
                    f"values, each {low:g}-{high:g} m."
                )
        if max(self.widths_m) >= min(self.distances_m):
            raise StudyDefinitionError(
                f"pointing.widths_m = {list(self.widths_m)}: each target must be narrower than "
                f"the shortest distance ({min(self.distances_m):g} m), or it covers the start."
            )
        if not 2 <= self.repetitions <= MOST_REPETITIONS:
            raise StudyDefinitionError(
                f"pointing.repetitions = {self.repetitions}: expected 2 to {MOST_REPETITIONS} "
                "(an effective width needs a spread)."
            )
        if not (math.isfinite(self.timeout_s) and 0 < self.timeout_s <= LONGEST_TIMEOUT_S):
            raise StudyDefinitionError(
                f"pointing.timeout_s = {self.timeout_s}: expected a time above 0 and at most "
                f"{LONGEST_TIMEOUT_S:g} s."
            )

    def block(self, person: int, study_seed: int = 0) -> tuple[PointingTrial, ...]:
        """Participant ``person``'s trials (numbered from 0 in the study's order) under any one
        lag, in the order they come: each repetition's cells shuffled for the person and the
        repetition. The seeds of study seed 0 are ``benchmarks/bench_fitts.py``'s since it
        began, so that its recorded results stay comparable."""
        cells = [(i, j) for i in range(len(self.distances_m)) for j in range(len(self.widths_m))]
        extra = [study_seed] if study_seed else []
        trials = []
        for rep in range(self.repetitions):
            for k in np.random.default_rng([person, rep, *extra]).permutation(len(cells)):
                i, j = cells[k]
                seed = 10_000_000 * study_seed + 10_000 * person + 100 * rep + 10 * i + j
                trials.append(PointingTrial(self.distances_m[i], self.widths_m[j], rep, seed))
        return tuple(trials)

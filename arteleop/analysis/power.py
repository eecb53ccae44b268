"""How many participants a design needs: power by resampling participants from a pilot.

A pool of participants (the experimental trials of one or more run folders, real or simulated)
is resampled with replacement, each participant's trials kept together, to studies of ``n``
participants; on each resampled study the tests ``arteleop analyze`` runs are run
(:mod:`arteleop.analysis.statistics`): each condition against the reference condition, per
measure, by the same method (untrimmed, with Lilliefors' choice between a t-test and its rank
counterpart; Yuen's trimmed means; or the thesis's dropped extremes), paired or not,
Holm-corrected within each family of pairwise tests where the analysis does; and the cue x
delay ANOVA for crossed designs. The share of resamples that reject
is the power for an effect *like the pool's*, with its binomial (Wilson) interval.

The tests are vectorised over resamples: resamples with the same number of values are tested
together by scipy's own functions (``axis=1``), so 1,000 resamples cost little more than one.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field

import numpy as np
import pandas as pd
from numpy.typing import NDArray
from scipy import stats

from arteleop.analysis.data import MEASURES, StudyData
from arteleop.analysis.delay import CELL_MEASURES, crossed_part, cue_sets, profiles, with_network
from arteleop.analysis.errors import AnalysisInputError
from arteleop.analysis.resampled_tests import (
    holm_reject,
    independent_p,
    paired_p,
    rm_anova_p,
    trim,
    trimmed_paired_p,
    yuen_p,
)
from arteleop.analysis.statistics import MIN_TEST_N, check_method

Array = NDArray[np.float64]
MAX_RESAMPLES = 100_000
CONFIDENCE = 0.95
"""Of the binomial intervals of the power."""


@dataclass(frozen=True)
class PowerOptions:
    """What to resample and test.

    Attributes:
        sizes: Participants per resampled study (each 3 or more).
        resamples: Resampled studies per size.
        alpha: Significance level of every test (0-1, exclusive).
        paired: Within-subject tests, as ``arteleop analyze --paired``.
        method: How two conditions are compared, as ``arteleop analyze --method``:
            ``untrimmed``, ``yuen`` or ``thesis``.
        holm: Holm-correct each family of pairwise tests, as ``arteleop analyze --holm``.
        compare: The conditions to compare with the reference; empty: every other one.
        reference: The condition the others are compared with.
        seed: Seeds the resampling.
    """

    sizes: tuple[int, ...] = (8, 12, 16, 20, 24, 28, 32, 36, 40)
    resamples: int = 1000
    alpha: float = 0.05
    paired: bool = False
    method: str = "untrimmed"
    holm: bool = False
    compare: tuple[str, ...] = ()
    reference: str = "none"
    seed: int = 0

    def __post_init__(self) -> None:
        if not self.sizes or min(self.sizes) < MIN_TEST_N:
            raise AnalysisInputError(
                f"sample sizes {list(self.sizes)}: each must be {MIN_TEST_N} or more (a test "
                f"needs {MIN_TEST_N} values)"
            )
        if not 1 <= self.resamples <= MAX_RESAMPLES:
            raise AnalysisInputError(f"resamples = {self.resamples}: expected 1 to {MAX_RESAMPLES}")
        if not (np.isfinite(self.alpha) and 0 < self.alpha < 1):
            raise AnalysisInputError(f"alpha = {self.alpha}: expected a level between 0 and 1")
        check_method(self.method, self.paired)


@dataclass(frozen=True)
class Pool:
    """Participants to resample: each one's value per measure and condition.

    Attributes:
        participants: Their ids, cohort-qualified where several sources were pooled.
        conditions: The conditions (cue set, and ``@profile`` in designs with several network
            profiles), the original's modalities first.
        networks: Each condition's network profile.
        values: Per measure, (participants, conditions): the successful experimental trial's
            value; NaN where the participant has none.
        sources: Where the pool came from, one line each.
    """

    participants: tuple[str, ...]
    conditions: tuple[str, ...]
    networks: tuple[str, ...]
    values: dict[str, Array] = field(repr=False)
    sources: tuple[str, ...] = ()


MIN_POOL = 4
"""Fewest participants with a successful experimental trial that power resamples. From k people
resampling draws at most C(2k - 1, k) different studies (1, 3 and 10 for k = 1, 2, 3), and one
person's groups have no spread at all: power would read 1 at every n."""


def check_pool_size(pool: Pool, names: str, coming: int = 0) -> None:
    """Refuse ``pool`` (from ``names``) if it has fewer than :data:`MIN_POOL` participants
    with a successful experimental trial, ``coming`` more participants counted in."""
    placed = np.zeros(len(pool.participants), dtype=bool)
    for values in pool.values.values():
        placed |= np.isfinite(values).any(axis=1)
    have = int(placed.sum())
    if have + coming >= MIN_POOL:
        return
    what = "no participant" if have == 0 else f"{have} participant(s)"
    raise AnalysisInputError(
        f"{names}: {what} with a successful experimental trial; power needs at least {MIN_POOL} "
        "to resample (from fewer too few different studies can be drawn, and one person's "
        "groups have no spread: power would read 1 at every n). Add participants, or "
        "--simulate N simulated ones of the first run folder's design"
    )


def make_pool(studies: Sequence[StudyData], names: Sequence[str]) -> Pool:
    """The pool of the experimental trials of ``studies`` (named ``names`` in the report)."""
    frames = []
    for k, data in enumerate(studies):
        trials = data.trials[data.trials["phase"] == "experimental"].copy()
        prefix = f"{k + 1}:" if len(studies) > 1 else ""
        trials["who"] = prefix + trials["participant"].astype(str)
        frames.append(trials)
    trials = with_network(pd.concat(frames, ignore_index=True))
    if trials.empty:
        raise AnalysisInputError(f"{', '.join(names)}: no experimental trials to resample")
    several = len(profiles(trials)) > 1
    conditions, networks = [], []
    for network in profiles(trials):
        here = trials[trials["network"] == network]
        for cues in cue_sets(trials):
            if (here["modality"] == cues).any():
                conditions.append(f"{cues}@{network}" if several else cues)
                networks.append(network)
    trials["condition"] = trials["modality"] + ("@" + trials["network"] if several else "")
    ok = trials[trials["outcome"] == "success"]
    people = tuple(dict.fromkeys(trials["who"]))
    values = {}
    for measure in MEASURES:
        if measure not in ok or not ok[measure].notna().any():
            continue
        wide = ok.pivot_table(index="who", columns="condition", values=measure, aggfunc="first")
        values[measure] = wide.reindex(index=people, columns=conditions).to_numpy(np.float64)
    lines = tuple(
        f"{name}: {data.trials['participant'].nunique()} participants"
        + (f" ({', '.join(data.sources)})" if data.sources else "")
        for name, data in zip(names, studies, strict=True)
    )  # fmt: skip
    return Pool(people, tuple(conditions), tuple(networks), values, lines)


# The resampling ---------------------------------------------------------------------------


def wilson(successes: NDArray, trials: int, confidence: float = CONFIDENCE) -> tuple[Array, Array]:
    """Wilson's interval of a binomial proportion."""
    z = stats.norm.ppf(0.5 + confidence / 2)
    p = successes / trials
    centre = (p + z**2 / (2 * trials)) / (1 + z**2 / trials)
    half = z * np.sqrt(p * (1 - p) / trials + z**2 / (4 * trials**2)) / (1 + z**2 / trials)
    return centre - half, centre + half


def comparisons(pool: Pool, options: PowerOptions) -> list[tuple[str, str]]:
    """(condition, reference) pairs: each asked-for condition against the reference of its
    network profile."""
    refs = {n: c for c, n in zip(pool.conditions, pool.networks, strict=True)
            if c.split("@")[0] == options.reference}  # fmt: skip
    if not refs:
        raise AnalysisInputError(
            f"reference {options.reference!r}: no such condition in the pool; its conditions: "
            f"{', '.join(pool.conditions)}"
        )
    bare = {c.split("@")[0] for c in pool.conditions}
    unknown = [c for c in options.compare if c not in pool.conditions and c not in bare]
    if unknown:
        raise AnalysisInputError(
            f"compare {unknown[0]!r}: no such condition in the pool; its conditions: "
            f"{', '.join(pool.conditions)}"
        )
    out = []
    for c, n in zip(pool.conditions, pool.networks, strict=True):
        name = c.split("@")[0]
        if name == options.reference or n not in refs:
            continue
        if options.compare and c not in options.compare and name not in options.compare:
            continue
        out.append((c, refs[n]))
    if not out:
        raise AnalysisInputError(f"nothing to compare with {options.reference!r} in the pool")
    return out


def power(pool: Pool, options: PowerOptions) -> Iterator[pd.DataFrame]:
    """Size after size: per comparison (and ANOVA effect) and measure, how many of the
    resampled studies reject, the power and its Wilson interval. A caller that stops early
    (Ctrl-C) keeps the sizes done."""
    pairs = comparisons(pool, options)
    rng = np.random.default_rng([options.seed, 45])
    for n in options.sizes:
        picks = rng.integers(0, len(pool.participants), size=(options.resamples, n))
        yield pd.DataFrame(_one_size(pool, options, pairs, picks))


def _one_size(
    pool: Pool, options: PowerOptions, pairs: list[tuple[str, str]], picks: NDArray[np.intp]
) -> list[dict]:
    test = _test(options)
    index = {c: i for i, c in enumerate(pool.conditions)}
    n = picks.shape[1]
    rows = []
    for measure, values in pool.values.items():
        sample = values[picks]  # (resamples, n, conditions)
        columns = {c: sample[:, :, index[c]] for c in pool.conditions}
        if options.method == "thesis":
            columns = {c: trim(v) for c, v in columns.items()}
        if options.holm:  # the family: every pair of conditions of a network profile
            for network in dict.fromkeys(pool.networks):
                family = [c for c, w in zip(pool.conditions, pool.networks, strict=True)
                          if w == network]  # fmt: skip
                every = list(itertools.combinations(family, 2))
                p = np.column_stack([test(columns[x], columns[y], options.alpha)
                                     for x, y in every])  # fmt: skip
                reject = holm_reject(p, options.alpha)
                for c, ref in pairs:
                    if ref in family:
                        k = every.index((c, ref) if (c, ref) in every else (ref, c))
                        rows.append(_row(f"{c} vs {ref}", measure, n, reject[:, k]))
        else:
            for c, ref in pairs:
                p = test(columns[c], columns[ref], options.alpha)
                rows.append(_row(f"{c} vs {ref}", measure, n, p <= options.alpha))
    rows += _anova_rows(pool, options, picks)
    return rows


def _test(options: PowerOptions) -> Callable[[Array, Array, float], Array]:
    """The vectorised test ``arteleop analyze`` runs with these options: (a, b, alpha) -> p."""
    if options.method == "yuen":
        robust = trimmed_paired_p if options.paired else yuen_p
        return lambda a, b, alpha: robust(a, b)
    return paired_p if options.paired else independent_p


def _anova_rows(pool: Pool, options: PowerOptions, picks: NDArray[np.intp]) -> list[dict]:
    if len(set(pool.networks)) < 2:
        return []
    design = {(c.split("@")[0], w) for c, w in zip(pool.conditions, pool.networks, strict=True)}
    cues, networks = crossed_part(design)
    if len(cues) < 2 or len(networks) < 2:
        return []
    rows = []
    for measure in CELL_MEASURES:
        if measure not in pool.values:
            continue
        values = pool.values[measure][picks]
        cells = [[values[:, :, pool.conditions.index(f"{c}@{w}")] for w in networks] for c in cues]
        cube = np.stack([np.stack(row, axis=-1) for row in cells], axis=-2)  # (r, n, cues, delays)
        for effect, p in rm_anova_p(cube).items():
            rows.append(_row(f"ANOVA {effect}", measure, picks.shape[1], p <= options.alpha))
    return rows


def _row(comparison: str, measure: str, n: int, reject: NDArray[np.bool_]) -> dict:
    hits = int(np.sum(reject))
    low, high = wilson(np.array(hits), len(reject))
    return {"comparison": comparison, "measure": measure, "n": n, "resamples": len(reject),
            "rejections": hits, "power": hits / len(reject),
            "ci_low": float(low), "ci_high": float(high)}  # fmt: skip


def smallest_n(table: pd.DataFrame, target: float) -> pd.DataFrame:
    """Per comparison and measure, the smallest n whose power reaches ``target`` (None if no
    size does)."""
    out = []
    for (comparison, measure), group in table.groupby(["comparison", "measure"], sort=False):
        reached = group[group["power"] >= target]["n"]
        out.append({"comparison": comparison, "measure": measure,
                    "n": int(reached.min()) if len(reached) else None})  # fmt: skip
    return pd.DataFrame(out)

"""The default study's answer over several cohorts: per modality the medians of time, error and
smoothness in each run, and each modality's effect against none pooled over the runs.

Reads only run folders (any lab's files of the format in docs/data-format.md). Each run is one
cohort; a participant is paired with themself (the modality's trial against their ``none``
trial), and the pairs of every cohort are pooled:

- time and error: the ratio of the modality to none, the geometric mean of the paired ratios
  with its 95 % t-interval (both are positive and skewed; below 1 is faster or more accurate);
- smoothness: the mean paired difference with its 95 % t-interval (LDLJ and SPARC: above 0 is
  smoother; submovements: below 0 is fewer; normalised jerk: below 0 is smoother, and it grows
  with duration).

Only experimental trials that succeeded under both the modality and none make a pair.

    arteleop study run --seed 1 --out run1   # and 2, 3
    python benchmarks/study_seeds.py run1 run2 run3
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np
import pandas as pd
from scipy import stats

from arteleop.analysis import AnalysisInputError, load_study

MODALITIES = ("none", "manipulation", "embodiment", "task", "full")
RATIOS = {"completion_time_s": "time", "placement_error_m": "error"}
DIFFERENCES = {
    "ldlj_xy": "LDLJ",
    "sparc_xy": "SPARC",
    "submovements_xy": "submovements",
    "normalized_jerk_xy": "normalised jerk",
}


def _load(paths: list[Path]) -> pd.DataFrame:
    frames = []
    for k, path in enumerate(paths):
        data = load_study(path)
        trials = data.trials[data.trials["phase"] == "experimental"].copy()
        trials["cohort"] = k
        if data.participants is not None:
            experts = data.participants.set_index("participant")
            expert = (experts["avr_hours"] >= 2) | (experts["games_hours"] >= 2)
            trials["expert"] = trials["participant"].map(expert).fillna(False).astype(bool)
        frames.append(trials)
    return pd.concat(frames, ignore_index=True)


def _medians(trials: pd.DataFrame, runs: int) -> str:
    rows = ["| run | modality | successes | time (s) | error (mm) | LDLJ | SPARC | submovements "
            "| normalised jerk |", "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]  # fmt: skip
    for k in range(runs):
        for m in MODALITIES:
            cell = trials[(trials["cohort"] == k) & (trials["modality"] == m)]
            ok = cell[cell["outcome"] == "success"]
            med = ok.median(numeric_only=True)
            rows.append(
                f"| {k + 1} | {m} | {len(ok)}/{len(cell)} | {med['completion_time_s']:.1f} | "
                f"{1000 * med['placement_error_m']:.1f} | {med['ldlj_xy']:.2f} | "
                f"{med['sparc_xy']:.2f} | {med['submovements_xy']:.0f} | "
                f"{med['normalized_jerk_xy']:.3g} |"
            )
    return "\n".join(rows)


def _interval(values: np.ndarray) -> tuple[float, float, float]:
    """Mean and its 95 % t-interval."""
    mean = float(np.mean(values))
    half = float(stats.t.ppf(0.975, len(values) - 1) * stats.sem(values))
    return mean, mean - half, mean + half


def _pairs(trials: pd.DataFrame, modality: str, column: str) -> np.ndarray:
    ok = trials[trials["outcome"] == "success"]
    wide = ok.pivot_table(index=["cohort", "participant"], columns="modality", values=column)
    both = wide[[modality, "none"]].dropna() if modality in wide else pd.DataFrame()
    return both.to_numpy() if len(both) else np.empty((0, 2))


def _effects(trials: pd.DataFrame) -> str:
    rows = ["| modality | measure | pairs | effect against none | 95 % CI | direction |",
            "| --- | --- | ---: | ---: | --- | --- |"]  # fmt: skip
    for m in MODALITIES[1:]:
        for column, label in {**RATIOS, **DIFFERENCES}.items():
            pairs = _pairs(trials, m, column)
            if len(pairs) < 3:
                rows.append(f"| {m} | {label} | {len(pairs)} | | | too few pairs |")
                continue
            if column in RATIOS:
                mean, low, high = np.exp(_interval(np.log(pairs[:, 0] / pairs[:, 1])))
                effect, ci = f"x {mean:.2f}", f"{low:.2f} to {high:.2f}"
                better = "lower" if high < 1 else "higher" if low > 1 else "no difference"
            else:
                mean, low, high = _interval(pairs[:, 0] - pairs[:, 1])
                effect, ci = f"{mean:+.3g}", f"{low:+.3g} to {high:+.3g}"
                better = "higher" if low > 0 else "lower" if high < 0 else "no difference"
            rows.append(f"| {m} | {label} | {len(pairs)} | {effect} | {ci} | {better} |")
    return "\n".join(rows)


def _experts(trials: pd.DataFrame) -> str:
    if "expert" not in trials:
        return "(no participants.csv: no expert groups)"
    rows = ["| modality | experts' median time (s) | others' (s) | gap (s) |",
            "| --- | ---: | ---: | ---: |"]  # fmt: skip
    ok = trials[trials["outcome"] == "success"]
    for m in MODALITIES:
        cell = ok[ok["modality"] == m]
        e = cell[cell["expert"]]["completion_time_s"].median()
        n = cell[~cell["expert"]]["completion_time_s"].median()
        rows.append(f"| {m} | {e:.1f} | {n:.1f} | {n - e:+.1f} |")
    return "\n".join(rows)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("runs", nargs="+", type=Path, help="run folders, one per cohort")
    args = parser.parse_args(argv)
    try:
        trials = _load(args.runs)
    except AnalysisInputError as err:
        print(f"study_seeds: {err}", file=sys.stderr)
        return 2
    print(f"{len(args.runs)} runs: {', '.join(str(p) for p in args.runs)}\n")
    print("## Medians per run and modality (successful experimental trials)\n")
    print(_medians(trials, len(args.runs)))
    print("\n## Each modality against none, pooled over the runs (paired by participant)\n")
    print(_effects(trials))
    print("\n## Experts and the others (pooled medians of time)\n")
    print(_experts(trials))
    return 0


if __name__ == "__main__":
    sys.exit(main())

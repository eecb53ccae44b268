"""A whole study: wall time on this machine's cores, and each trial's simulated-to-wall ratio.

Runs a study (the built-in default: 22 participants x (3 practice + 5 modalities) = 176 trials)
with ``--workers`` processes, then its analysis, and prints:

- the study's wall clock against the baseline of the same trials run one after another, which is
  the sum of the trials' own wall times measured in the same run;
- each trial's batch speed (simulated s per wall s, medians per phase);
- per modality, the median completion time and placement error, and the analysis's p-values
  against no AR, beside the original study's directions (docs/explanation/study.md §6).

    python benchmarks/bench_study.py [--participants 22] [--workers 2] [--out DIR]
"""

from __future__ import annotations

from arteleop import blas_kernel  # noqa: F401  (first: it picks numpy's BLAS kernel)

# isort: split
import os

os.environ.setdefault("OMP_NUM_THREADS", "1")

import argparse
import tempfile
import time
from dataclasses import replace
from pathlib import Path

import numpy as np
import pandas as pd

from arteleop.analysis import AnalysisOptions, analyse, load_study
from arteleop.study import CohortConfig, StudyConfig, run_study

DIRECTIONS = {
    "manipulation": "more accurate than none",
    "embodiment": "smoothest hand",
    "task": "little help",
    "full": "faster and more accurate than none",
}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--participants", type=int, default=22)
    parser.add_argument("--workers", type=int, default=os.cpu_count() or 1)
    parser.add_argument("--out", type=Path, default=None)
    args = parser.parse_args()
    study = StudyConfig()
    if args.participants != study.cohort.size:
        n = args.participants
        experts = round(7 * n / 22)
        cohort = CohortConfig(size=n, avr_experts=experts, games_experts=experts,
                              both_experts=round(4 * n / 22))  # fmt: skip
        study = replace(study, cohort=cohort)
    out = args.out or Path(tempfile.mkdtemp(prefix="bench-study-")) / "run"
    start = time.perf_counter()
    run = run_study(study, out, workers=args.workers)
    study_wall_s = time.perf_counter() - start
    t0 = time.perf_counter()
    result = analyse(load_study(out), AnalysisOptions())
    analysis_s = time.perf_counter() - t0
    sim = np.array([s for s, _ in run.speed])
    wall = np.array([w for _, w in run.speed])
    series_s = wall.sum()
    print(f"study: {len(run.trials)} trials, {len(set(run.trials['participant']))} participants, "
          f"{sim.sum():.0f} simulated s; run folder {out}\n")  # fmt: skip
    print("| run | wall clock (min) | simulated s per wall s | vs baseline |")
    print("| --- | ---: | ---: | ---: |")
    print(f"| trials one after another (baseline: the sum of their wall times) | "
          f"{series_s / 60:.1f} | {sim.sum() / series_s:.2f} | 1.00 |")  # fmt: skip
    print(f"| {args.workers} workers, study + analysis ({analysis_s:.0f} s) | "
          f"{(study_wall_s + analysis_s) / 60:.1f} | {sim.sum() / study_wall_s:.2f} | "
          f"{series_s / (study_wall_s + analysis_s):.2f} |\n")  # fmt: skip
    ratio = sim / wall
    print("| trial batch speed (simulated s / wall s) | median | p10 | p90 |")
    print("| --- | ---: | ---: | ---: |")
    print(f"| all trials | {np.median(ratio):.2f} | {np.percentile(ratio, 10):.2f} | "
          f"{np.percentile(ratio, 90):.2f} |\n")  # fmt: skip
    trials = run.trials
    print("outcomes: " + ", ".join(f"{k} {v}" for k, v in trials["outcome"].value_counts().items()))
    exp = trials[trials["phase"] == "experimental"]
    tests = result.tests
    print(
        "\n| modality | success | median time (s) | median error (mm) | median jerk | "
        "p time vs none | p error vs none | original study's direction |"
    )
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | --- |")
    for modality in study.modalities:
        group = exp[exp["modality"] == modality]
        ok = group[group["outcome"] == "success"]
        row = [modality, f"{len(ok)}/{len(group)}", f"{ok['completion_time_s'].median():.1f}",
               f"{1000 * ok['placement_error_m'].median():.1f}",
               f"{ok['normalized_jerk_xy'].median():.3g}"]  # fmt: skip
        for measure in ("completion_time_s", "placement_error_m"):
            row.append(_p(tests, measure, modality))
        row.append(DIRECTIONS.get(modality, ""))
        print("| " + " | ".join(row) + " |")


def _p(tests: pd.DataFrame, measure: str, modality: str) -> str:
    if modality == "none":
        return ""
    pick = tests[(tests["subset"] == "all") & (tests["measure"] == measure)
                 & (tests["group_a"].isin(["none", modality]))
                 & (tests["group_b"].isin(["none", modality]))]  # fmt: skip
    if pick.empty or pd.isna(pick["p_value"].iloc[0]):
        return "-"
    return f"{pick['p_value'].iloc[0]:.3f}{pick['stars'].iloc[0] or ''}"


if __name__ == "__main__":
    main()

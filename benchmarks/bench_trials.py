"""Synthetic trials per modality: outcomes, completion time, placement error, smoothness, speed.

Runs the synthetic operator through full headless trials, ``--seeds`` per modality, and prints
the medians per modality (the columns of trials.csv that a trial knows, through
``TrialResult.to_row``) and the batch speed (simulated seconds per wall second, one core).

    python benchmarks/bench_trials.py [--seeds 5] [--modalities none,manipulation,...]
"""

from __future__ import annotations

import os

os.environ.setdefault("OMP_NUM_THREADS", "1")

import argparse
import time

import numpy as np
import pandas as pd

from arteleop.ar_features import MODALITIES
from arteleop.scene import RemoteSite
from arteleop.teleop import TrialConfig, run_trial, trial_operator


def run(modalities: list[str], seeds: int) -> pd.DataFrame:
    rows = []
    for modality in modalities:
        for seed in range(seeds):
            config = TrialConfig(modality=modality, seed=seed)
            with RemoteSite(config.site) as site:
                source = trial_operator(site, config)
                t0 = time.perf_counter()
                result = run_trial(source, config, site)
                wall = time.perf_counter() - t0
            rows.append({**result.to_row(), "speed": result.duration_s / wall})
            print(
                f"  {modality:12s} seed {seed}: {rows[-1]['outcome']}, "
                f"{rows[-1]['completion_time_s']:.1f} s, "
                f"{rows[-1]['placement_error_m'] * 1000:.1f} mm",
                flush=True,
            )
    return pd.DataFrame(rows)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--seeds", type=int, default=5)
    parser.add_argument("--modalities", default=",".join(MODALITIES))
    args = parser.parse_args()
    if hasattr(os, "sched_setaffinity"):
        os.sched_setaffinity(0, {min(os.sched_getaffinity(0))})
    df = run(args.modalities.split(","), args.seeds)
    print(f"\n## Synthetic trials, {args.seeds} seeds per modality, medians over the successes\n")
    print(
        "| modality | successes | completion time (s) | placement error (mm) "
        "| normalised jerk x-y | hand path (m) | batch speed (x real time) |"
    )
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: |")
    for modality, group in df.groupby("modality", sort=False):
        ok = group[group["outcome"] == "success"]
        print(
            f"| {modality} | {len(ok)}/{len(group)} | {ok['completion_time_s'].median():.1f} "
            f"| {ok['placement_error_m'].median() * 1000:.1f} "
            f"| {ok['normalized_jerk_xy'].median():.3g} | {ok['hand_path_length_m'].median():.2f} "
            f"| {group['speed'].median():.1f} |"
        )
    others = df[df["outcome"] != "success"]
    if len(others):
        print("\nNot successes: " + ", ".join(
            f"{r.modality} seed {r.seed} {r.outcome}" for r in others.itertuples()
        ))  # fmt: skip
    print(f"\nBatch speed over all trials: median {np.median(df['speed']):.1f}x real time.")


if __name__ == "__main__":
    main()

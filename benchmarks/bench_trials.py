"""Synthetic trials per modality: outcomes, completion time, placement error, smoothness, speed.

Runs the synthetic operator through full headless trials, ``--seeds`` per modality, and prints
the medians per modality (the columns of trials.csv that a trial knows, through
``TrialResult.to_row``) and the batch speed (simulated seconds per wall second, one core).

    python benchmarks/bench_trials.py [--seeds 5] [--modalities none,manipulation,...]
    python benchmarks/bench_trials.py --ab-tracker-gate [--seeds 5]

``--ab-tracker-gate`` runs every trial twice, side by side: as the loop runs it (the tracker's
renders skipped while its model sees none of the bowl) and the plain way (every look rendered),
and prints whether the outcomes and numbers agree, and the wall times.
"""

from __future__ import annotations

from arteleop import blas_kernel  # noqa: F401  (first: it picks numpy's BLAS kernel)

# isort: split
import os

os.environ.setdefault("OMP_NUM_THREADS", "1")

import argparse
import time
from dataclasses import replace

import numpy as np
import pandas as pd

from arteleop.ar_features import MODALITIES
from arteleop.scene import RemoteSite
from arteleop.teleop import TrialConfig, run_trial, trial_operator


def trial(config: TrialConfig) -> dict[str, object]:
    """One synthetic trial's row, its wall time (s) and batch speed."""
    with RemoteSite(config.site) as site:
        source = trial_operator(site, config)
        t0 = time.perf_counter()
        result = run_trial(source, config, site)
        wall = time.perf_counter() - t0
    return {
        **result.to_row(),
        "wall_s": wall,
        "speed": result.duration_s / wall,
        "renders_skipped": result.counts["tracker_renders_skipped"],
    }


def ab_tracker_gate(modalities: list[str], seeds: int) -> None:
    """The tracker's render gate against every look rendered, on the same trials."""
    rows = []
    for modality in modalities:
        for seed in range(seeds):
            config = TrialConfig(modality=modality, seed=seed)
            gated = trial(config)
            plain = trial(replace(config, skip_hidden_tracker_renders=False))
            same = all(
                gated[k] == plain[k] or (gated[k] != gated[k] and plain[k] != plain[k])
                for k in ("outcome", "completion_time_s", "placement_error_m", "normalized_jerk_xy")
            )
            rows.append((modality, seed, gated, plain, same))
            print(f"  {modality:12s} seed {seed}: same {same}", flush=True)
    print("\n## Tracker render gate: gated (the default) vs every look rendered (baseline)\n")
    print(
        "| modality | seed | outcome | completion time (s) gated / plain "
        "| placement error (mm) gated / plain | identical row | renders skipped "
        "| wall (s) gated / plain | speed-up |"
    )
    print("| --- | ---: | --- | ---: | ---: | --- | ---: | ---: | ---: |")
    for modality, seed, g, p, same in rows:
        print(
            f"| {modality} | {seed} | {g['outcome']} / {p['outcome']} "
            f"| {g['completion_time_s']:.2f} / {p['completion_time_s']:.2f} "
            f"| {g['placement_error_m'] * 1000:.2f} / {p['placement_error_m'] * 1000:.2f} "
            f"| {'yes' if same else 'NO'} | {g['renders_skipped']} "
            f"| {g['wall_s']:.1f} / {p['wall_s']:.1f} | {p['wall_s'] / g['wall_s']:.2f} |"
        )
    wall_g = np.median([g["wall_s"] for _, _, g, _, _ in rows])
    wall_p = np.median([p["wall_s"] for _, _, _, p, _ in rows])
    print(
        f"\nIdentical rows: {sum(r[4] for r in rows)}/{len(rows)}. Median wall time per trial: "
        f"gated {wall_g:.1f} s, plain {wall_p:.1f} s (ratio {wall_p / wall_g:.2f})."
    )


def run(modalities: list[str], seeds: int) -> pd.DataFrame:
    rows = []
    for modality in modalities:
        for seed in range(seeds):
            rows.append(trial(TrialConfig(modality=modality, seed=seed)))
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
    parser.add_argument("--ab-tracker-gate", action="store_true")
    args = parser.parse_args()
    if hasattr(os, "sched_setaffinity"):
        os.sched_setaffinity(0, {min(os.sched_getaffinity(0))})
    if args.ab_tracker_gate:
        ab_tracker_gate(args.modalities.split(","), args.seeds)
        return
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

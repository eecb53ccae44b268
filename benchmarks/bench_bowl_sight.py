"""Fits the tracker model's threshold (``BowlSightConfig.min_visible_fraction``) to the tracker.

Runs seeded synthetic trials through the real loop and, every ``--every-s`` of simulated time,
asks both the bowl tracker (a rendered head-camera frame, :class:`~arteleop.scene.BowlTracker`)
and its ray model (:meth:`RemoteSite.sight_bowl`) whether the camera sees the bowl; the model's
answer is the fraction of its surface points that rays from the camera reach. Prints, for each
candidate threshold, how often the model agrees with the tracker and how it disagrees; the
threshold is the one that agrees best. Nothing of a study goes into it: only the tracker.

    python benchmarks/bench_bowl_sight.py [--seeds 6] [--modalities none,full] [--every-s 0.5]

The defaults are the fit behind ``BowlSightConfig.min_visible_fraction``: six seeds of each of
the five modalities (30 trials), a look every 0.5 s.
"""

from __future__ import annotations

from arteleop import blas_kernel  # noqa: F401  (first: it picks numpy's BLAS kernel)

# isort: split
import os

os.environ.setdefault("OMP_NUM_THREADS", "1")

import argparse
import multiprocessing
from concurrent.futures import ProcessPoolExecutor

import numpy as np
import pandas as pd

from arteleop.scene import BowlSight, BowlTracker, RemoteSite
from arteleop.study import MODALITY_NAMES
from arteleop.teleop import TrialConfig, TrialProgress, run_trial, trial_operator


def looks(modality: str, seed: int, every_s: float) -> list[dict]:
    """One trial's looks: the model's visible fraction and the tracker's answer."""
    config = TrialConfig(modality=modality, seed=seed)
    rows: list[dict] = []
    with RemoteSite(config.site) as site:
        tracker = BowlTracker(site.config.workspace.bowl)
        z = site.config.workspace.table_top_z_m
        n_points = BowlSight(site.config.workspace.bowl, site.config.bowl_sight).n_surface_points
        period = round(every_s * config.rates.camera_hz)

        def look(status: TrialProgress) -> None:
            if round(status.time_s * config.rates.camera_hz) % period:
                return
            model = site.sight_bowl()
            rows.append(
                {
                    "trial": f"{modality}/{seed}",
                    "time_s": status.time_s,
                    "fraction": model.n_points / n_points,
                    "tracker": tracker.track(site.capture(), z).found,
                }
            )

        run_trial(trial_operator(site, config), config, site, progress=look)
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=6)
    parser.add_argument("--modalities", default=",".join(MODALITY_NAMES))
    parser.add_argument("--every-s", type=float, default=0.5)
    args = parser.parse_args()
    calls = [(m, s) for m in args.modalities.split(",") for s in range(args.seeds)]
    with ProcessPoolExecutor(2, mp_context=multiprocessing.get_context("fork")) as pool:
        futures = [pool.submit(looks, m, s, args.every_s) for m, s in calls]
        frames = pd.DataFrame([row for f in futures for row in f.result()])
    tracker = frames["tracker"].to_numpy()
    table = []
    for threshold in (0.02, 0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4, 0.5):
        model = frames["fraction"].to_numpy() >= threshold
        table.append(
            {
                "min_visible_fraction": threshold,
                "agree": (model == tracker).mean(),
                "model only": (model & ~tracker).sum(),
                "tracker only": (~model & tracker).sum(),
            }
        )
    print(
        f"{len(frames)} looks in {frames['trial'].nunique()} trials; the tracker finds the bowl "
        f"in {tracker.mean():.0%}"
    )
    print(pd.DataFrame(table).to_string(index=False, float_format=lambda v: f"{v:.3f}"))
    print("agreement per trial at the best threshold:")
    best = table[int(np.argmax([row["agree"] for row in table]))]["min_visible_fraction"]
    agree = (frames["fraction"] >= best) == frames["tracker"]
    print(agree.groupby(frames["trial"]).mean().round(3).to_string())


if __name__ == "__main__":
    main()

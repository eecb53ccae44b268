"""What the head camera shows during a trial: the bowl and the gripper, per phase.

Runs seeded synthetic trials and, at every camera frame, asks whether the camera sees the bowl
(the tracker's model, ``RemoteSite.sight_bowl``, which agrees with the tracker on 99 % of
frames, tests/scene/test_bowl_sight.py) and the gripper (in the image and the sensor's depth
range). Prints, per phase of the task, the fraction of frames in which each is visible, and the
trials' outcomes. ``--start X Y`` and ``--target X Y`` try other points (base frame, m).

    python benchmarks/bench_visibility.py [--seeds 3] [--modalities none,full] [--start X Y]
        [--target X Y]
"""

from __future__ import annotations

from arteleop import blas_kernel  # noqa: F401  (first: it picks numpy's BLAS kernel)

# isort: split
import os

os.environ.setdefault("OMP_NUM_THREADS", "1")

import argparse
from collections.abc import Callable
from dataclasses import replace

import pandas as pd

from arteleop.operator import SyntheticSource
from arteleop.scene import RemoteSite, SiteConfig, Workspace
from arteleop.teleop import TrialConfig, TrialProgress, run_trial, trial_operator

PHASES = {
    "reach": "reach", "descend": "reach",
    "close": "grasp", "lift": "grasp",
    "transport": "transport",
    "lower": "place", "open": "place",
}  # fmt: skip
"""The pick-and-place's phases (the synthetic operator's), grouped as the original's."""


def _looker(
    site: RemoteSite, source: SyntheticSource, modality: str, rows: list[dict]
) -> Callable[[TrialProgress], None]:
    """At each camera tick of a trial, what the camera shows, by the operator's phase."""

    def look(status: TrialProgress) -> None:
        phase = PHASES.get(source.operator.phase)
        if phase is None:
            return
        state = site.observe()
        rows.append(
            {
                "modality": modality,
                "phase": phase,
                "bowl": site.sight_bowl().found,
                "gripper": state.camera.sees(state.gripper_m),
            }
        )

    return look


def run(modalities: list[str], seeds: int, workspace: Workspace) -> tuple[pd.DataFrame, list[str]]:
    rows, outcomes = [], []
    for modality in modalities:
        for seed in range(seeds):
            config = TrialConfig(modality=modality, seed=seed, site=SiteConfig(workspace=workspace))
            with RemoteSite(config.site) as site:
                source = trial_operator(site, config)

                look = _looker(site, source, modality, rows)
                result = run_trial(source, config, site, progress=look)
                outcomes.append(
                    f"{modality}/{seed}: {result.outcome.value}, "
                    f"{result.placement_error_true_m * 1000:.0f} mm (true)"
                )
    return pd.DataFrame(rows), outcomes


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=3)
    parser.add_argument("--modalities", default="none,full")
    parser.add_argument("--start", type=float, nargs=2, metavar=("X", "Y"))
    parser.add_argument("--target", type=float, nargs=2, metavar=("X", "Y"))
    args = parser.parse_args()
    ws = Workspace()
    if args.start:
        ws = replace(ws, start_xy_m=tuple(args.start))
    if args.target:
        ws = replace(ws, target_xy_m=tuple(args.target))
    frames, outcomes = run(args.modalities.split(","), args.seeds, ws)
    table = frames.groupby(["modality", "phase"], sort=False)[["bowl", "gripper"]].mean()
    table["frames"] = frames.groupby(["modality", "phase"], sort=False).size()
    print(f"start {ws.start_xy_m}, target {ws.target_xy_m}; fraction of camera frames visible:")
    print(table.round(2).to_string())
    print("\n".join(outcomes))


if __name__ == "__main__":
    main()

"""What a mis-registered head camera does to a study, and what calibration gives back.

Runs one small study three times, the same participants and trial seeds each time:
- ``perfect``: the system knows the camera's true pose;
- ``offset``: the system's camera pose is off by ``--offset-mm`` and ``--offset-deg``;
- ``calibrated``: the pose ``arteleop calibrate`` finds (``camera_graph`` in the study file),
  with the same offset given, which the calibration does not see.
It prints, per registration, the medians of the trials' co-location error, the outcomes, the
completion times and the tracked and true placement errors; the same per modality; and the
true placement error's change against ``perfect`` trial by trial (Wilcoxon signed-rank test over
the pairs where both succeeded).

    python benchmarks/bench_registration.py [--participants 6] [--out arteleop-registration]
        [--offset-mm 20 0 0] [--offset-deg 0 2 0] [--workers 2]

A run folder that is already complete is read again rather than re-run.
"""

from __future__ import annotations

from arteleop import blas_kernel  # noqa: F401  (first: it picks numpy's BLAS kernel)

# isort: split
import argparse
import json
from pathlib import Path

import numpy as np
import pandas as pd
from scipy.stats import wilcoxon

from arteleop.ar_features import MODALITIES
from arteleop.cli import main as arteleop

CONDITIONS = ("perfect", "offset", "calibrated")


def study_text(
    condition: str, participants: int, offset_mm: list[float], offset_deg: list[float]
) -> str:
    registration = {
        "perfect": "",
        "offset": f"camera_offset_mm = {offset_mm}\ncamera_offset_deg = {offset_deg}\n",
        "calibrated": 'camera_graph = "calibration.json"\n',
    }[condition]
    experts = max(1, participants // 3)
    return (
        f'name = "registration: {condition}"\nseed = 0\n{registration}'
        "[familiarization]\ntrials = 0\n"
        f"[cohort]\nsize = {participants}\navr_experts = {experts}\n"
        f"games_experts = {experts}\nboth_experts = {experts // 2}\n"
    )


def finished(run: Path) -> bool:
    manifest = run / "manifest.json"
    return manifest.is_file() and bool(json.loads(manifest.read_text()).get("finished"))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--participants", type=int, default=6)
    parser.add_argument("--out", type=Path, default=Path("arteleop-registration"))
    parser.add_argument("--offset-mm", type=float, nargs=3, default=[20.0, 0.0, 0.0])
    parser.add_argument("--offset-deg", type=float, nargs=3, default=[0.0, 2.0, 0.0])
    parser.add_argument("--workers", type=int, default=0)
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    offsets = ["--camera-offset-mm", *map(str, args.offset_mm),
               "--camera-offset-deg", *map(str, args.offset_deg)]  # fmt: skip
    graph = args.out / "calibration.json"
    if not graph.is_file():
        arteleop(["calibrate", "--out", str(graph), *offsets])
    for condition in CONDITIONS:
        run = args.out / f"run-{condition}"
        if finished(run):
            continue
        study = args.out / f"{condition}.toml"
        study.write_text(study_text(condition, args.participants, args.offset_mm, args.offset_deg))
        code = arteleop(["study", "run", str(study), "--out", str(run),
                         "--workers", str(args.workers), "--quiet"])  # fmt: skip
        if code != 0:
            raise SystemExit(f"the {condition} study failed (exit {code})")
    trials = {
        c: pd.read_csv(args.out / f"run-{c}" / "trials.csv").set_index(["participant", "modality"])
        for c in CONDITIONS
    }
    print(
        f"\nOne study of {args.participants} participants x 5 modalities, three registrations of "
        f"the head camera (offset: {args.offset_mm} mm, {args.offset_deg} deg, camera frame).\n"
    )
    print("| registration | co-location (px) | co-location (mm) | successes | completion (s) "
          "| tracked error (mm) | true error (mm) |")  # fmt: skip
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: |")
    for condition, t in trials.items():
        ok = t[t.outcome == "success"]
        print(
            f"| {condition} | {t.colocation_error_px.median():.1f} "
            f"| {t.colocation_error_m.median() * 1000:.1f} | {len(ok)}/{len(t)} "
            f"| {ok.completion_time_s.median():.1f} | {ok.placement_error_m.median() * 1000:.1f} "
            f"| {ok.placement_error_true_m.median() * 1000:.1f} |"
        )
    print("\nPer modality: successes, and the median true placement error of the successes (mm).\n")
    print("| modality | " + " | ".join(CONDITIONS) + " |")
    print("| --- |" + " ---: |" * len(CONDITIONS))
    for modality in MODALITIES:
        cells = []
        for condition in CONDITIONS:
            t = trials[condition].xs(modality, level="modality")
            ok = t[t.outcome == "success"]
            error = f"{ok.placement_error_true_m.median() * 1000:.0f}" if len(ok) else "-"
            cells.append(f"{len(ok)}/{len(t)}, {error}")
        print(f"| {modality} | " + " | ".join(cells) + " |")
    base = trials["perfect"]
    print("\nTrue placement error against perfect, trial by trial (pairs where both succeeded):\n")
    print("| registration | pairs | median change (mm) | Wilcoxon p |")
    print("| --- | ---: | ---: | ---: |")
    for condition in CONDITIONS[1:]:
        t = trials[condition]
        both = t[t.outcome == "success"].index.intersection(base[base.outcome == "success"].index)
        diff = t.loc[both, "placement_error_true_m"] - base.loc[both, "placement_error_true_m"]
        p = f"{wilcoxon(diff).pvalue:.3f}" if len(both) >= 6 else "-"
        print(f"| {condition} | {len(both)} | {np.median(diff) * 1000:+.1f} | {p} |")


if __name__ == "__main__":
    main()

"""What the simulated participants saw of their own misses, per cue set: how often a last look at
the display a trial ended on left them sure they had missed (``saw_miss`` in trials.csv), and
the placement error (ground truth) of the trials they saw missed and of those they did not. A
cue that shows a miss clearly teaches the participant to be more careful in its next trials; one
that blurs it does not (docs/explanation/operator-model.md, knowing one's misses).

    python benchmarks/read_misses_seen.py RUN [RUN ...]
"""

from __future__ import annotations

import arteleop  # noqa: F401  first: it picks numpy's BLAS kernel (arteleop/blas_kernel.py)

# isort: split
import argparse
import sys
from pathlib import Path

import pandas as pd

from arteleop.analysis import AnalysisInputError
from arteleop.analysis.data import load_study


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("runs", nargs="+", type=Path, help="run folders of simulated cohorts")
    args = parser.parse_args()
    try:
        trials = pd.concat([load_study(run / "trials.csv").trials for run in args.runs])
    except AnalysisInputError as err:
        print(f"read_misses_seen: {err}", file=sys.stderr)
        return 2
    trials = trials[trials["saw_miss"].notna()]
    if trials.empty:
        print("read_misses_seen: no trial says whether its participant saw a miss (saw_miss).")
        return 2
    print("| phase | cues | trials | saw a miss | true error, seen missed (median mm) | true "
          "error, not (median mm) |")  # fmt: skip
    print("| --- | --- | --- | --- | --- | --- |")
    for (phase, cues), group in trials.groupby(["phase", "modality"], sort=True):
        seen = group["saw_miss"] == 1
        error_mm = 1000 * group["placement_error_true_m"]
        print(f"| {phase} | {cues} | {len(group)} | {seen.mean():.0%} | "
              f"{error_mm[seen].median():.1f} | {error_mm[~seen].median():.1f} |")  # fmt: skip
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""A study's answer beside the same study with one constant changed: each cue set against no AR
(time and error, the geometric mean of the paired ratios with its 95 % t-interval, as
``arteleop analyze`` pools cohorts), the model's run first, then each sensitivity run, and each
condition's median time and error.

Run the same study and seed with the constant at half and at twice its value
(``[operator_params]`` or ``[operator]`` in the study file), then:

    python benchmarks/read_sensitivity.py MODEL_RUN RUN_HALF RUN_TWICE ...
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from arteleop.analysis import AnalysisInputError
from arteleop.analysis.cohorts import pool_cohorts, pooled_effects
from arteleop.analysis.data import load_study


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("runs", nargs="+", type=Path, help="run folders, the model's first")
    args = parser.parse_args()
    cells: dict[str, list[str]] = {}
    for run in args.runs:
        try:
            trials = pool_cohorts([load_study(run / "trials.csv")])
        except AnalysisInputError as err:
            print(f"read_sensitivity: {err}", file=sys.stderr)
            return 2
        ok = trials[trials["outcome"] == "success"]
        medians = ok.groupby("modality")[["completion_time_s", "placement_error_m"]].median()
        for cues, m in medians.iterrows():
            cells.setdefault(f"{cues}: median", []).append(
                f"{m['completion_time_s']:.1f} s, {1000 * m['placement_error_m']:.1f} mm"
            )
        for _, e in pooled_effects(trials).iterrows():
            if e["measure"] in ("time", "error"):
                cells.setdefault(f"{e['modality']}: {e['measure']} against none", []).append(
                    f"x {e['effect']:.2f} ({e['low']:.2f}-{e['high']:.2f})"
                )
    print("| | " + " | ".join(run.name for run in args.runs) + " |")
    print("| --- |" + " --- |" * len(args.runs))
    for name, row in cells.items():
        print(f"| {name} | " + " | ".join(row) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main())

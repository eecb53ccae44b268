"""A short pointing study served to the scripted pointer in a real browser, its run folder
analysed, beside the simulated participant on the same trials.

The study (``--out``'s ``study.toml``): one participant, one target 0.2 m from the start cross
and 60 mm wide (``--distance-m``, ``--width-m``), twice under each of two lags (0 and 150 ms round trip), the depth aids on (the
script finds the gripper over the table by their ring), 400 s a trial (the script looks again
after every go, about 10 s each on two cores). Then, as a researcher types them:

1. ``arteleop study serve study.toml --out served --port 0``, and the scripted pointer
   (``tests/instruments/scripted_pointer.py``) takes part in headless Chromium from the consent
   page to the last, deciding every move from what the page shows; a screenshot of every page
   goes to ``--out``'s ``shots/``;
2. ``arteleop analyze served``: the served folder, as any lab's pointing table;
3. ``arteleop study run study.toml --out simulated``: the simulated participant on the same
   plan (the same targets and seeds), and ``arteleop analyze served simulated``.

It prints, per trial, the movement time and the selection's distance from the target's middle
in the browser against the simulated participant's; it exits non-zero if a step fails, a page's
outcome is not the file's, or a trial's selection did not count.

    python benchmarks/bench_scripted_pointing.py [--out DIR] [--seed N] [--distance-m D]
        [--width-m W]

Needs Chromium and Tesseract (the tests' system packages). About 12 min on two cores.
"""

from __future__ import annotations

from arteleop import blas_kernel  # noqa: F401  (first: it picks numpy's BLAS kernel)

# isort: split
import argparse
import math
import sys
import tempfile
from pathlib import Path

import pandas as pd
from bench_scripted_study import (  # benchmarks/, the script's folder; it puts tests/ on the path
    BenchmarkFailed,
    arteleop,
    serve_to_script,
)

from tests.instruments.scripted_pointer import ScriptedPointer

STUDY_TOML = """\
name = "scripted-pointing"
task = "pointing"
seed = {seed}
depth_aids = true
participants = [{{id = "F00"}}]

[pointing]
distances_m = [{distance_m}]
widths_m = [{width_m}]
repetitions = 2
timeout_s = 400.0

[[conditions]]
cues = []
round_trip_ms = 0

[[conditions]]
cues = []
round_trip_ms = 150
"""


def _said(row: pd.Series) -> str:
    """What the page says of a counted selection in ``pointing.csv``'s ``row``."""
    off_mm = 1000 * math.hypot(row.along_m, row.across_m)
    where = "inside" if row.hit == 1 else "outside"
    return f"Chosen in {row.movement_time_s:.2f} s, {off_mm:.0f} mm from the middle: {where}"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=None, help="a new folder for the files")
    parser.add_argument("--seed", type=int, default=0, help="the study's seed: its trials")
    parser.add_argument("--distance-m", type=float, default=0.2, help="the target's distance (m)")
    parser.add_argument("--width-m", type=float, default=0.06, help="the target's width (m)")
    args = parser.parse_args()
    out = args.out or Path(tempfile.mkdtemp(prefix="bench-pointing-"))
    out.mkdir(parents=True, exist_ok=True)
    study, served, simulated = out / "study.toml", out / "served", out / "simulated"
    design = {"seed": args.seed, "distance_m": args.distance_m, "width_m": args.width_m}
    study.write_text(STUDY_TOML.format(**design), encoding="utf-8")
    (shots := out / "shots").mkdir(exist_ok=True)

    print(f"serving {study} to the scripted pointer into {served}", flush=True)
    done, session_s, _ = serve_to_script(study, served, shots, (640, 480), None, ScriptedPointer)
    people = pd.read_csv(served / "pointing.csv")
    if len(done) != len(people):
        raise BenchmarkFailed(f"{len(done)} trials done on the page, {len(people)} in pointing.csv")
    for page, row in zip(done, people.itertuples(), strict=True):
        if row.outcome == "selected" and not page.outcome.startswith(_said(row)):
            raise BenchmarkFailed(f"{page.heading}: the page said {page.outcome!r}, "
                                  f"pointing.csv holds {_said(row)!r}")  # fmt: skip
    arteleop("analyze", str(served), "--out", str(served / "report"))
    arteleop("study", "run", str(study), "--out", str(simulated), "--quiet")
    arteleop("analyze", str(served), str(simulated), "--out", str(out / "both"))
    print(f"analysed {served}; the simulated participant in {simulated}; both in {out / 'both'}")

    model = pd.read_csv(simulated / "pointing.csv")
    print(f"\nscripted session: {session_s:.0f} s of wall time, consent to the last page\n")
    print(f"{'trial':<7}{'lag (ms)':>9}{'browser: MT (s) / off (mm)':>30}"
          f"{'simulated: MT / off':>24}")  # fmt: skip
    for a, b in zip(people.itertuples(), model.itertuples(), strict=True):
        if (a.trial, a.seed) != (b.trial, b.seed):
            raise BenchmarkFailed(f"trial {a.trial}: the cohorts' plans differ")
        cells = [
            f"{r.movement_time_s:.2f} / {1000 * math.hypot(r.along_m, r.across_m):.0f}"
            if r.movement_time_s == r.movement_time_s
            else "-"
            for r in (a, b)
        ]
        print(f"{a.trial:<7}{a.round_trip_ms:>9g}{cells[0]:>30}{cells[1]:>24}")
    missed = people[people.outcome != "selected"]
    if len(missed):
        raise BenchmarkFailed(
            f"the scripted pointer's selection did not count in trials {missed.trial.tolist()} "
            f"({missed.outcome.tolist()}): the pages it saw are in {shots}"
        )
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except BenchmarkFailed as err:
        sys.exit(f"bench_scripted_pointing: {err}")

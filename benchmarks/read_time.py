"""Where a pick-and-place trial's time goes: the default study's experimental trials under one
cue set, rerun one by one (the study's own traits, seeds and sites), each with its time per phase
and, over the phases up to the release, per activity of the simulated participant (moving,
watching the display come to rest, looking; :data:`~arteleop.operator.ACTIVITIES`), its looks
and its corrections. The mean of each over the trials follows.

    python benchmarks/read_time.py [--seed 1] [--modality none] [--trials 12]
"""

from __future__ import annotations

from arteleop import blas_kernel  # noqa: F401  (first: it picks numpy's BLAS kernel)

# isort: split
import os

os.environ.setdefault("OMP_NUM_THREADS", "1")

import argparse
import sys
from collections import defaultdict

from arteleop.ar_features import STUDY_MODALITIES
from arteleop.operator import ACTIVITIES
from arteleop.scene import RemoteSite
from arteleop.study import StudyConfig
from arteleop.study.protocol import operator_traits, trial_config
from arteleop.study.run_opening import plan_run
from arteleop.study.sites import StudySite
from arteleop.teleop import run_trial, trial_operator

AFTER_RELEASE = ("retract", "home")
"""Phases after the release: the trial's timer has stopped by their end or runs past them."""


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seed", type=int, default=1, help="the default study's seed")
    parser.add_argument("--modality", default="none", choices=STUDY_MODALITIES)
    parser.add_argument("--trials", type=int, default=12, help="the first N participants' trials")
    args = parser.parse_args()
    if args.trials < 1:
        print(f"read_time: --trials {args.trials}: expected 1 or more.", file=sys.stderr)
        return 2
    study = StudyConfig(seed=args.seed)
    site = StudySite()
    plan, cohort = plan_run(study, site)
    people = {p.id: p for p in cohort}
    specs = [s for s in plan if s.modality == args.modality and s.phase == "experimental"]
    totals: defaultdict[str, float] = defaultdict(float)
    for spec in specs[: args.trials]:
        config = trial_config(study, site, spec)
        with RemoteSite(config.site) as remote:
            traits = operator_traits(study, people[spec.participant])
            source = trial_operator(remote, config, traits=traits)
            result = run_trial(source, config, remote)
        phases = []
        for record in source.operator.history:
            end_s = result.duration_s if record.end_s is None else record.end_s
            phases.append(f"{record.name} {end_s - record.start_s:.1f}")
            totals[f"phase {record.name}"] += end_s - record.start_s
            if record.name not in AFTER_RELEASE:
                for activity in ACTIVITIES:
                    totals[activity] += record.activity_s[activity]
                totals["looks"] += record.looks
                totals["corrections"] += record.corrections
        totals["completion time"] += result.completion_time_s
        print(f"{spec.participant} {result.outcome.value} {result.completion_time_s:.1f} s: "
              + ", ".join(phases))  # fmt: skip
    n = min(args.trials, len(specs))
    print(f"mean over {n} trials (s, or counts), the activities up to the release:")
    phases_first = sorted(totals, key=lambda name: not name.startswith("phase"))
    for name in phases_first:
        print(f"  {name}: {totals[name] / n:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

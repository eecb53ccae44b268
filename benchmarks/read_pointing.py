"""Read pointing trials one by one: how each look of the simulated participant ended, and where
the selection landed.

Runs the Fitts task of ``bench_fitts.py`` for one cell (``--distance-m``, ``--width-m``, no
added lag) for its first ``--people`` people and ``--reps`` repetitions (the bench's traits and
seeds), the person having seen ``--seen MISSES/TRIALS`` outcomes before (what knowing one's
misses carries; ``0/0``: none). For each trial it prints whether the selection hit, how far off
it landed along and across the task axis (mm), the movement time, the corrections and looks,
and each look's verdict: ``sure`` (sure enough of being within), ``gained-nothing`` (looking
longer gained nothing: accept if judged within), ``unsure`` (sure enough of being outside) or
``too-long`` (``max_look_s`` reached), whether it accepted or corrected, and how sure it was.

    python benchmarks/read_pointing.py [--people 4] [--reps 2] [--distance-m 0.4]
        [--width-m 0.01] [--seen 5/20]
"""

from __future__ import annotations

from arteleop import blas_kernel  # noqa: F401  (first: it picks numpy's BLAS kernel)

# isort: split
import argparse
from dataclasses import replace

from bench_fitts import DISTANCES_M, WIDTHS_M, block_trials, person_traits  # benchmarks/

from arteleop.errors import ConfigurationError
from arteleop.operator import (
    OperatorParams,
    SeenOutcomes,
    believed_error_scale,
)
from arteleop.operator.simulated import look as look_module
from arteleop.operator.simulated.belief import averaging_saturated
from arteleop.study.pointing_design import MOST_PEOPLE, MOST_REPETITIONS
from arteleop.teleop.pointing import run_pointing_trial

VERDICTS: list[tuple[str, float]] = []


def _logging_verdict(verdict):  # type: ignore[no-untyped-def]
    """``Look.verdict``, each verdict given kept in :data:`VERDICTS` with its reason."""

    def logged(self, time_s, sure, variance_m2, judged_within):  # type: ignore[no-untyped-def]
        looked_too_long = time_s - self.start_s >= self.max_look_s
        result = verdict(self, time_s, sure, variance_m2, judged_within)
        if result is not None:
            # As Look.verdict decides: sure enough accepts; a look that gains nothing accepts
            # an error judged within, whatever else holds; else unsure or too long corrects.
            confidence = self.traits.confidence
            saturated = averaging_saturated(self._first_variance_m2, variance_m2, self._glances)
            reason = ("sure" if sure >= confidence
                      else "gained-nothing" if saturated
                      else "unsure" if sure <= 1 - confidence
                      else "too-long" if looked_too_long else "?")  # fmt: skip
            VERDICTS.append((f"{reason} ({'accept' if result else 'correct'})", sure))
        return result

    return logged


def seen_outcomes(text: str) -> SeenOutcomes:
    try:
        misses, trials = (int(x) for x in text.split("/"))
        return SeenOutcomes(trials, misses)
    except (ValueError, ConfigurationError) as err:
        raise argparse.ArgumentTypeError(
            f"{text!r}: expected MISSES/TRIALS, whole numbers, misses at most trials ({err})"
        ) from None


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--people", type=int, default=4, help="people (1 or more)")
    parser.add_argument("--reps", type=int, default=2, help="repetitions (2 to 99)")
    parser.add_argument("--distance-m", type=float, default=0.4, choices=DISTANCES_M)
    parser.add_argument("--width-m", type=float, default=0.01, choices=WIDTHS_M)
    parser.add_argument("--seen", type=seen_outcomes, default=SeenOutcomes(),
                        help="outcomes seen before, MISSES/TRIALS (default 0/0)")  # fmt: skip
    args = parser.parse_args()
    if not (1 <= args.people <= MOST_PEOPLE and 2 <= args.reps <= MOST_REPETITIONS):
        parser.error(f"--people {args.people} --reps {args.reps}: give 1 to {MOST_PEOPLE} people "
                     f"and 2 to {MOST_REPETITIONS} repetitions")  # fmt: skip
    look_module.Look.verdict = _logging_verdict(look_module.Look.verdict)
    params = replace(OperatorParams(), seen_outcomes=args.seen)
    print("| person | rep | error scale | hit | along (mm) | across (mm) | MT (s) | corrections "
          "| looks | verdicts (how sure) |")  # fmt: skip
    print("| --- " * 10 + "|")
    for person in range(args.people):
        traits = person_traits(person)
        scale = believed_error_scale(args.seen, traits.confidence, params.own_error_prior_sd)
        cell = [t for t in block_trials(person, args.reps)
                if (t.distance_m, t.width_m) == (args.distance_m, args.width_m)]  # fmt: skip
        for trial in sorted(cell, key=lambda t: t.rep):
            rep = trial.rep
            VERDICTS.clear()
            r = run_pointing_trial(trial.distance_m, trial.width_m, traits, trial.seed,
                                   params=params)  # fmt: skip
            said = ", ".join(f"{why} {sure:.2f}" for why, sure in VERDICTS)
            print(f"| F{person:02d} | {rep} | {scale:.2f} | {'yes' if r.hit else 'no'} "
                  f"| {1000 * r.along_m:+.1f} | {1000 * r.across_m:+.1f} "
                  f"| {r.movement_time_s:.2f} | {r.corrections} | {r.looks} | {said} |")  # fmt: skip


if __name__ == "__main__":
    main()

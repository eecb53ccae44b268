"""The display's lag as the operator lives it: how late the gripper it sees follows the hand it
meant to move, through the whole loop.

The simulated participant does the Fitts pointing task (``bench_fitts.py``'s cells) under each
round-trip network delay. At every sample the operator's intended hand (its efference copy,
mapped to the gripper it commands) and the gripper the display shows it (in the cloud, with the
frame's age) are kept. The lag is the time shift that best aligns the two paths' displacements
over 0.1 s windows (in steps of the operator's sample, 10 ms), over the whole trial: what an operator who predicts the
display from its own movement has to allow for. Beside it, what the operator came to believe
by the trial's end (its lag learnt from the display's responses).

``OperatorParams.familiar_lag_s`` is the median at zero added delay: the lag the operator knows
from practice on the system (docs/explanation/operator-model.md).

    python benchmarks/bench_display_lag.py [--people 4] [--lags 0,225] [--workers 2]
"""

from __future__ import annotations

from arteleop import blas_kernel  # noqa: F401  (first: it picks numpy's BLAS kernel)

# isort: split
import argparse
import os
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass

import numpy as np

from arteleop.ar_features import DisplayFrame
from arteleop.operator import SyntheticSource, WearableSample

DISTANCES_M = (0.1, 0.2, 0.4)
WIDTHS_M = (0.01, 0.02, 0.04)
WINDOW_S = 0.1
SEARCH_S = 1.0
"""Shifts are searched up to the added lag plus this (s)."""


class WatchedSource(SyntheticSource):
    """A synthetic operator that keeps, at each sample, its intended hand and the gripper the
    display showed it in the cloud (None where it showed none: the pointing trials draw no
    ghost)."""

    def __init__(self, *args, **kwargs) -> None:
        super().__init__(*args, **kwargs)
        self.seen: list[tuple[float, np.ndarray, np.ndarray | None]] = []

    def sample(self, time_s: float, view: DisplayFrame) -> WearableSample | None:
        from arteleop.operator.simulated.perception import shown_gripper_m

        out = super().sample(time_s, view)
        shown = shown_gripper_m(view) if view.gripper_in_camera else None
        self.seen.append((time_s, self.operator.hand.intended_m.copy(), shown))
        return out


@dataclass(frozen=True)
class Job:
    person: int
    distance_m: float
    width_m: float
    lag_ms: float
    seed: int


def best_shift_s(
    time_s: np.ndarray, meant_m: np.ndarray, shown_m: np.ndarray, longest_s: float
) -> float:
    """The shift (s, a whole number of samples up to ``longest_s``) by which the shown path's
    displacements best match the meant path's, compared over the same samples at every shift."""
    step = float(np.median(np.diff(time_s)))
    w = max(1, round(WINDOW_S / step))
    ks = np.arange(round(longest_s / step) + 1)
    shown_d = (shown_m[w:] - shown_m[:-w])[ks[-1] :]
    use = np.all(np.isfinite(shown_d), axis=1)
    if not use.any():
        raise SystemExit("no displayed gripper to align: the display never showed it moving")
    costs = []
    for k in ks:
        meant = meant_m[ks[-1] - k : len(meant_m) - k]
        meant_d = meant[w:] - meant[:-w]
        costs.append(float(np.sum((shown_d[use] - meant_d[use]) ** 2)))
    return float(ks[int(np.argmin(costs))] * step)


def run(job: Job) -> dict[str, float]:
    """One pointing trial: the shift that aligns the shown gripper with the meant one, and the
    lag the operator believed at the end."""
    from arteleop.operator import Expertise, TraitDistribution
    from arteleop.robot.mapping import HandToGripper
    from arteleop.scene import RemoteSite
    from arteleop.teleop import run_trial
    from arteleop.teleop.pointing import pointing_config, pointing_source

    traits = TraitDistribution().draw(0, f"F{job.person:02d}", Expertise())
    config = pointing_config(job.distance_m, job.width_m, job.seed, job.lag_ms / 1000)
    with RemoteSite(config.site) as site:
        source = pointing_source(config, site.observe().gripper_m, traits, WatchedSource)
        run_trial(source, config, site)
    mapping = HandToGripper(config.controller.mapping)
    time_s = np.array([t for t, _, _ in source.seen])
    # The gripper the intended hand commands (the mapping's position part).
    meant = np.array([mapping.offset_m + mapping.config.scale * h for _, h, _ in source.seen])
    shown = np.array([np.full(3, np.nan) if s is None else s for _, _, s in source.seen])
    shift = best_shift_s(time_s, meant, shown, job.lag_ms / 1000 + SEARCH_S)
    return {"shift_s": shift, "believed_s": source.operator.lag_s}


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--people", type=int, default=4, help="simulated people (1 or more)")
    parser.add_argument("--lags", default="0,225", help="round-trip lags (ms), comma-separated")
    parser.add_argument("--workers", type=int, default=len(os.sched_getaffinity(0)))
    args = parser.parse_args()
    try:
        lags = [float(x) for x in args.lags.split(",")]
    except ValueError:
        parser.error(f"--lags {args.lags!r}: give milliseconds separated by commas, e.g. 0,225")
    if args.people < 1 or args.workers < 1 or min(lags) < 0:
        parser.error("--people and --workers take 1 or more, --lags 0 ms or more")
    jobs = [Job(p, d, w, lag, seed=10000 * p + 10 * i + j) for lag in lags
            for p in range(args.people) for i, d in enumerate(DISTANCES_M)
            for j, w in enumerate(WIDTHS_M)]  # fmt: skip
    with ProcessPoolExecutor(args.workers) as pool:
        rows = [dict(vars(job), **r) for job, r in zip(jobs, pool.map(run, jobs), strict=True)]
    cells = len(DISTANCES_M) * len(WIDTHS_M)
    print(f"{len(rows)} pointing trials, {args.people} people x {cells} cells per lag\n")
    print("| added lag (ms) | display lag, median (range) (s) | believed at the end (s) |")
    print("| ---: | ---: | ---: |")
    for lag in lags:
        shift = np.array([r["shift_s"] for r in rows if r["lag_ms"] == lag])
        believed = np.array([r["believed_s"] for r in rows if r["lag_ms"] == lag])
        print(f"| {lag:.0f} | {np.median(shift):.3f} ({shift.min():.3f}-{shift.max():.3f}) "
              f"| {np.median(believed):.3f} ({believed.min():.3f}-{believed.max():.3f}) |")  # fmt: skip


if __name__ == "__main__":
    main()

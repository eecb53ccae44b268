"""The simulated participant's Fitts pointing task, through the whole teleoperation chain.

Wearable -> network -> reconstruction -> IK -> robot -> camera -> display frame -> operator:
targets are circles drawn on the table (distance D along +y from a start drawn as a cross,
diameter W); the operator brings the gripper 5 cm over the cross, points at the circle at that
height and selects by closing the gripper.
Each simulated person (traits drawn as a study draws them) does every cell ``--reps`` times per
lag, in one block per lag: each repetition's cells in an order shuffled for the person, the same
orders and the same seeds at every lag (paired). Through a block the person carries the lag it
has learnt from one trial to the next (its belief at a trial's end is its belief at the next
one's start), as people practise the lag of a block; the first trial of a block meets the lag
with the belief from practice on the system (``familiar_lag_s``). It also carries what it saw of
its outcomes: told of a miss, as Fitts experiments tell it, it trusts its judgement less and is
more careful (``arteleop.operator.simulated.own_errors``). ``--fresh`` makes every trial the block's
first. ``--depth-aids`` draws the depth aids in every trial.

Measured as ISO 9241-9 asks (Soukoreff & MacKenzie 2004): the selection is the closure the
operator decided (an earlier closure, the fingers pushed by the table, is a slip, counted); per
person and cell the effective width ``W_e = 4.133 SD`` of the selections' 2-D endpoints
projected on the task axis, the effective distance ``D_e`` their mean, ``ID_e = log2(D_e / W_e +
1)`` and the movement time (the median of the repetitions); per cell the medians over people.
Per lag it fits ``MT = a + b ID_e`` over the cells, then MacKenzie & Ware's (CHI 1993) two lag
models over every lag (lag adding to movement time, ``MT = a + b ID + c lag``, or multiplying
the index of difficulty, ``MT = a + (b + c lag) ID``), and each lag's effect on movement time
against no lag, person by person (geometric mean of the paired ratios, 95 % t-interval). Last,
where the movement time goes, per lag and width: the operator's time moving, watching the display
settle, looking and waiting, with its corrections and looks.

    python benchmarks/bench_fitts.py [--people 16] [--reps 5] [--lags 0,75,150,225,450]
                                     [--quick] [--fresh] [--depth-aids] [--workers 2]
                                     [--own-error-prior-sd SD] [--max-look-s S]
                                     [--json OUT.json] [--csv pointing.csv]

The design is a pointing study's (``arteleop.study.pointing_run``; at the defaults,
docs/examples/fitts_lag.toml, which ``arteleop study run`` runs to the same trials): this script
adds its timing, the model's own account (slips, through a block, where the time goes) and
options a study file has not (``--fresh``, ``--own-error-prior-sd``, ``--max-look-s``).

What it prints is what the model predicts: no constant of the operator is fitted to it.
"""

from __future__ import annotations

from arteleop import blas_kernel  # noqa: F401  (first: it picks numpy's BLAS kernel)

# isort: split
import argparse
import json
import os
import sys
import time
from dataclasses import replace

import numpy as np
import pandas as pd

from arteleop.analysis.pointing import (
    POINTING_COLUMNS,
    cell_medians,
    fitts_fits,
    lag_effect,
    lag_models,
    person_cells,
)
from arteleop.operator import ACTIVITIES, OperatorParams, OperatorTraits
from arteleop.study import StudyConfig
from arteleop.study.definition import ConditionSpec, ParticipantSpec
from arteleop.study.pointing_design import (
    MOST_PEOPLE,
    MOST_REPETITIONS,
    PointingDesign,
    PointingTrial,
)
from arteleop.study.pointing_run import pointing_blocks, run_blocks
from arteleop.study.protocol import operator_traits

DISTANCES_M = (0.1, 0.2, 0.4)
WIDTHS_M = (0.01, 0.02, 0.04)


def fitts_study(people: int, reps: int, lags: list[float], depth_aids: bool = False) -> StudyConfig:
    """The bench's design as a pointing study (docs/examples/fitts_lag.toml at the defaults):
    people F00, F01, ... (novices at their own speed, traits drawn from seed 0), every cell
    ``reps`` times per lag (ms)."""
    return StudyConfig(
        name="bench_fitts", task="pointing", depth_aids=depth_aids,
        participants=tuple(ParticipantSpec(f"F{p:02d}") for p in range(people)),
        conditions=tuple(ConditionSpec(round_trip_ms=lag) for lag in lags),
        pointing=PointingDesign(DISTANCES_M, WIDTHS_M, reps),
    )  # fmt: skip


def block_trials(person: int, reps: int) -> tuple[PointingTrial, ...]:
    """A person's trials in a block (the study's :meth:`PointingDesign.block`)."""
    return PointingDesign(DISTANCES_M, WIDTHS_M, reps).block(person)


def person_traits(person: int) -> OperatorTraits:
    """The traits of the bench's simulated person ``person`` (F00, F01, ...), as the study
    draws them."""
    study = fitts_study(person + 1, 2, [0.0])
    return operator_traits(study, study.participants[person])


def parse_lags(text: str) -> list[float]:
    try:
        lags = [float(x) for x in text.split(",") if x.strip()]
    except ValueError:
        lags = []
    if (not lags or len(set(lags)) < len(lags)
            or any(not np.isfinite(x) or x < 0 or x > 2000 for x in lags)):  # fmt: skip
        raise argparse.ArgumentTypeError(
            f"{text!r}: give different round-trip lags in ms, 0-2000, separated by commas "
            "(e.g. 0,75,150)"
        )
    return lags


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--people", type=int, default=16, help="simulated people (1 or more)")
    parser.add_argument("--reps", type=int, default=5, help="repetitions of a cell (2 or more)")
    parser.add_argument("--lags", type=parse_lags, default=[0.0, 75.0, 150.0, 225.0, 450.0],
                        help="round-trip lags (ms), comma-separated; the first is the baseline")  # fmt: skip
    parser.add_argument("--quick", action="store_true",
                        help="4 people, 3 repetitions, the lags 0 and 225 ms: a few minutes")  # fmt: skip
    parser.add_argument("--fresh", action="store_true",
                        help="every trial meets its lag anew: no practice within a block")  # fmt: skip
    parser.add_argument("--depth-aids", action="store_true",
                        help="draw the depth aids (drop line, ring, height label) in every trial")  # fmt: skip
    parser.add_argument("--own-error-prior-sd", type=float, metavar="SD",
                        help="the operator's prior SD on the log of its error scale, in place "
                             "of its own (a sensitivity run; above 0)")  # fmt: skip
    parser.add_argument("--max-look-s", type=float, metavar="S",
                        help="the longest look (s), in place of the operator's own (a "
                             "sensitivity run; above 0)")  # fmt: skip
    parser.add_argument("--workers", type=int, default=len(os.sched_getaffinity(0)))
    parser.add_argument("--json", help="write the lag table, the fits and the cells to this file")
    parser.add_argument("--csv", help="write the trials to this file as a pointing study's table "
                        "(pointing.csv: 'arteleop analyze FILE' reads it)")  # fmt: skip
    args = parser.parse_args()
    if not 1 <= args.people <= MOST_PEOPLE:
        parser.error(f"--people {args.people}: give 1 to {MOST_PEOPLE}")
    if not 2 <= args.reps <= MOST_REPETITIONS:
        parser.error(f"--reps {args.reps}: give 2 to {MOST_REPETITIONS} (an effective width "
                     "needs a spread)")  # fmt: skip
    sd = args.own_error_prior_sd
    if sd is not None and not (np.isfinite(sd) and sd > 0):
        parser.error(f"--own-error-prior-sd {sd}: give a number above 0 (the SD of a log)")
    look_s = args.max_look_s
    if look_s is not None and not (np.isfinite(look_s) and look_s > 0):
        parser.error(f"--max-look-s {look_s}: give a number of seconds above 0")
    if args.workers < 1:
        parser.error(f"--workers {args.workers}: give 1 or more")
    people, reps, lags = (4, 3, [0.0, 225.0]) if args.quick else (args.people, args.reps, args.lags)
    params = OperatorParams()
    if sd is not None:
        params = replace(params, own_error_prior_sd=sd)
    if look_s is not None:
        params = replace(params, max_look_s=look_s)
    blocks = [replace(b, fresh=args.fresh, params=params)
              for b in pointing_blocks(fitts_study(people, reps, lags, args.depth_aids))]  # fmt: skip
    t0 = time.perf_counter()
    rows = [_bench_row(row) for row in run_blocks(blocks, args.workers)]
    print(f"{len(rows)} pointing trials, {people} people x {reps} repetitions, in "
          f"{time.perf_counter() - t0:.0f} s on {args.workers} workers\n")  # fmt: skip
    report(rows, lags, args.json, args.csv)


def _bench_row(row: dict) -> dict:
    """A study's row with the bench's own keys: the person's number, the lag, whether it
    selected; a trial with no selection is a miss through a block."""
    selected = bool(np.isfinite(row["movement_time_s"]))
    return {**row, "person": int(str(row["participant"])[1:]), "lag_ms": row["round_trip_ms"],
            "selected": float(selected), "hit": row["hit"] if selected else 0.0}  # fmt: skip


def pointing_table(rows: list[dict]) -> pd.DataFrame:
    """The trials as a pointing study's table (docs/reference/data-format.md, ``pointing.csv``):
    what ``arteleop analyze`` reads of people's pointing, and analyses the same way."""
    table = pd.DataFrame(rows)[list(POINTING_COLUMNS)]
    table.loc[table["movement_time_s"].isna(), "hit"] = np.nan
    return table


def slips(rows: list[dict], keys: tuple[str, ...]) -> dict[tuple, float]:
    """The slips (closures before the decision: the simulated participant's own account) per
    value of ``keys`` among lag_ms, person, distance_m, width_m."""
    out: dict[tuple, float] = {}
    for r in rows:
        key = tuple(r[k] for k in keys)
        out[key] = out.get(key, 0.0) + r["slips"]
    return out


def last_beliefs(rows: list[dict], lag: float) -> list[float]:
    """Per person, the lag it believed at the end of its block under ``lag`` (s)."""
    last: dict[int, float] = {}
    for r in rows:  # in each block's order
        if r["lag_ms"] == lag:
            last[r["person"]] = r["believed_lag_s"]
    return list(last.values())


MW_RATIO_AT_225_MS = 1.64
"""People's movement time under 225 ms of lag against none, pointing with a mouse (MacKenzie &
Ware, CHI 1993: +64 %). Both of their lag models are linear in the lag at a given ID."""


def people_ratio(lag_ms: float, own_lag_s: float) -> float:
    """The yardstick: people's movement time under ``lag_ms`` added to a display whose own lag
    is ``own_lag_s`` (s), against none added, on MacKenzie & Ware's line (taken past their 225 ms
    where the total lag is longer: not a fit, a comparison)."""
    slope_per_s = (MW_RATIO_AT_225_MS - 1) / 0.225
    return (1 + slope_per_s * (own_lag_s + lag_ms / 1000)) / (1 + slope_per_s * own_lag_s)


def report(
    rows: list[dict], lags: list[float], json_path: str | None, csv_path: str | None
) -> None:
    table = pointing_table(rows)
    if csv_path:
        table.to_csv(csv_path, index=False)
    people = person_cells(table)
    cells = cell_medians(people)
    cell_slips = slips(rows, ("lag_ms", "distance_m", "width_m"))
    timeouts = sum(1 for r in rows if not r["selected"])
    if timeouts:
        print(f"{timeouts} trials ended without a selection (timeout); left out\n")
    fits: dict[str, object] = {}
    lines = fitts_fits(cells).set_index("round_trip_ms")
    for lag in lags:
        here = cells[cells["round_trip_ms"] == lag]
        print(f"## Lag {lag:g} ms (medians over people)\n")
        print("| D (m) | W (mm) | ID (bits) | W_e (mm) | ID_e (bits) | MT (s) | errors | slips "
              "| timeouts |")  # fmt: skip
        print("| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
        for c in here.itertuples():
            n_slips = cell_slips.get((lag, c.distance_m, c.width_m), 0.0)
            print(f"| {c.distance_m:.1f} | {1000 * c.width_m:.0f} | {c.id_bits:.2f} "
                  f"| {1000 * c.we_m:.1f} | {c.id_e_bits:.2f} | {c.mt_s:.2f} "
                  f"| {100 * c.error_rate:.0f} % | {n_slips:.0f} | {c.timeouts} |")  # fmt: skip
        if lag in lines.index:
            f = lines.loc[lag]
            key = "" if lag == lags[0] else f"_{lag:g}ms"
            fits[f"fitts_effective{key}"] = {"a_s": f.a_s_effective,
                                             "b_s_per_bit": f.b_s_per_bit_effective,
                                             "r2": f.r2_effective}  # fmt: skip
            fits[f"fitts_nominal{key}"] = {"a_s": f.a_s_nominal,
                                           "b_s_per_bit": f.b_s_per_bit_nominal,
                                           "r2": f.r2_nominal}  # fmt: skip
            print(f"\nMT = {f.a_s_effective:.2f} s + {f.b_s_per_bit_effective:.2f} s/bit x ID_e, "
                  f"R^2 = {f.r2_effective:.2f} (nominal ID: {f.a_s_nominal:.2f} s + "
                  f"{f.b_s_per_bit_nominal:.2f} s/bit, R^2 = {f.r2_nominal:.2f})\n")  # fmt: skip

    own_lag_s = OperatorParams().familiar_lag_s  # the display's lag with none added, measured
    per_lag: dict[str, list] = {"lag_ms": [], "movement_time_s": [], "error_rate": [],
                                "ratio": [], "ratio_low": [], "ratio_high": [],
                                "believed_lag_s": [], "people_ratio": []}  # fmt: skip
    lag_slips = slips(rows, ("lag_ms",))
    print("## Under added lag (round trip)\n")
    print(
        f"The yardstick: people's ratio on MacKenzie & Ware's line (+64 % at 225 ms), from this "
        f"display's own lag of {own_lag_s:.3f} s (docs/explanation/operator-model.md).\n"
    )
    print("| lag (ms) | MT (s, median of cells) | MT / no lag, paired by person (95 % CI) | people "
          "| yardstick | errors | slips | lag believed at the end (s) |")  # fmt: skip
    print("| ---: | ---: | --- | ---: | ---: | ---: | ---: | ---: |")
    for lag in lags:
        c = cells[cells["round_trip_ms"] == lag]
        if c.empty:
            continue
        mt = float(np.median(c["mt_s"].to_numpy()))
        err = float(np.mean(c["error_rate"].to_numpy()))
        ratio, low, high, n = lag_effect(people, lag, lags[0])
        believed = float(np.median(last_beliefs(rows, lag)))
        yardstick = people_ratio(lag, own_lag_s)
        values = (lag, mt, err, ratio, low, high, believed, yardstick)
        for key, value in zip(per_lag, values, strict=True):
            per_lag[key].append(value)
        print(f"| {lag:g} | {mt:.2f} | x {ratio:.2f} ({low:.2f}-{high:.2f}) | {n} | "
              f"x {yardstick:.2f} | {100 * err:.0f} % | {lag_slips.get((lag,), 0.0):.0f} | "
              f"{believed:.2f} |")  # fmt: skip
    if len(per_lag["lag_ms"]) > 1:
        models = lag_models(cells)
        fits.update(models)
        for name, m in models.items():
            print(f"\n{name}: a = {m['a_s']:.2f} s, b = {m['b_s_per_bit']:.2f} s/bit, "
                  f"c = {m['c']:.2f}, R^2 = {m['r2']:.3f}")  # fmt: skip
    breakdown = time_breakdown(rows, lags)
    through = through_blocks(rows, lags)
    if json_path:
        with open(json_path, "w", encoding="utf-8") as f:
            # NaN (a cell with too few selections) is not JSON: null.
            def records(df: pd.DataFrame) -> list[dict]:
                return df.astype(object).where(df.notna(), None).to_dict("records")

            json.dump({**per_lag, "fits": fits, "cells": records(cells),
                       "people": records(people), "breakdown": breakdown,
                       "through_blocks": through}, f, indent=1)  # fmt: skip
        print(f"\nwrote {json_path}")


def through_blocks(rows: list[dict], lags: list[float]) -> list[dict]:
    """Per lag and third of the block (in the order the trials ran), the error rate, the median
    movement time of the selected trials and the mean error scale the person began them with
    (what its misses so far taught it); printed as a table."""
    out = []
    print("\n## Through a block (trials in the order they ran)\n")
    print("| lag (ms) | third | trials | errors | MT (s) | error scale |")
    print("| ---: " * 6 + "|")
    for lag in lags:
        blocks: dict[int, list[dict]] = {}
        for r in rows:  # in each block's order
            if r["lag_ms"] == lag:
                blocks.setdefault(r["person"], []).append(r)
        for third in range(3):
            part = [r for block in blocks.values()
                    for r in np.array_split(np.array(block, dtype=object), 3)[third]]  # fmt: skip
            if not part:
                continue
            done = [r["movement_time_s"] for r in part if r["selected"]]
            entry = {"lag_ms": lag, "third": third + 1, "trials": len(part),
                     "error_rate": float(1 - np.mean([r["hit"] for r in part])),
                     "mt_s": float(np.median(done)) if done else float("nan"),
                     "error_scale": float(np.mean([r["error_scale"] for r in part]))}  # fmt: skip
            out.append(entry)
            print(f"| {lag:g} | {third + 1} | {len(part)} | {100 * entry['error_rate']:.0f} % | "
                  f"{entry['mt_s']:.2f} | {entry['error_scale']:.2f} |")  # fmt: skip
    return out


def time_breakdown(rows: list[dict], lags: list[float]) -> list[dict]:
    """Per lag and target width, where the movement time of the selected trials went: the mean
    seconds in each of the operator's activities (they add up to the mean movement time), and
    the mean corrections and looks per trial; printed as a table."""
    out = []
    print("\n## Where the movement time goes (means over the selected trials)\n")
    print("| lag (ms) | W (mm) | trials | MT (s) | " + " | ".join(f"{a} (s)" for a in ACTIVITIES)
          + " | corrections | looks |")  # fmt: skip
    print("| ---: " * (6 + len(ACTIVITIES)) + "|")
    for lag in lags:
        for w in WIDTHS_M:
            done = [r for r in rows if r["lag_ms"] == lag and r["width_m"] == w and r["selected"]]
            if not done:
                continue
            entry = {"lag_ms": lag, "W_m": w, "trials": len(done)}
            for key in ("movement_time_s", *(f"{a}_s" for a in ACTIVITIES), "corrections",
                        "looks"):  # fmt: skip
                entry[key] = float(np.mean([r[key] for r in done]))
            out.append(entry)
            print(f"| {lag:g} | {1000 * w:.0f} | {len(done)} | {entry['movement_time_s']:.2f} | "
                  + " | ".join(f"{entry[f'{a}_s']:.2f}" for a in ACTIVITIES)
                  + f" | {entry['corrections']:.1f} | {entry['looks']:.1f} |")  # fmt: skip
    return out


if __name__ == "__main__":
    sys.exit(main())

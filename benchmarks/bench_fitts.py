"""The simulated participant's Fitts pointing task, through the whole teleoperation chain.

Wearable -> network -> reconstruction -> IK -> robot -> camera -> display frame -> operator:
targets are circles drawn on the table (distance D from a start point, diameter W), the
operator points at them with the gripper 5 cm above the table and selects by closing it. Each
simulated person (traits drawn as a study draws them) does every cell once per lag.

Per cell it prints the movement time (start of the pointing movement to the selection), the
error rate (selections outside the circle) and the effective index of difficulty
``ID_e = log2(D_e / W_e + 1)``, ``W_e = 4.133 SD`` of the endpoints along the task axis
(ISO 9241-9; Soukoreff & MacKenzie 2004), then fits ``MT = a + b ID_e`` over the cells. Under
added lag (round trip) it prints movement time and error rate per lag and fits MacKenzie &
Ware's (CHI 1993) two models: lag adding to movement time (``MT = a + b ID + c lag``) and lag
multiplying the index of difficulty (``MT = a + (b + c lag) ID``).

    python benchmarks/bench_fitts.py [--people 10] [--lags 0,75,150,225] [--quick]
                                     [--workers 2] [--json OUT.json]

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
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass

import numpy as np

DISTANCES_M = (0.1, 0.2, 0.4)
WIDTHS_M = (0.01, 0.02, 0.04)


@dataclass(frozen=True)
class Job:
    person: int
    distance_m: float
    width_m: float
    lag_ms: float
    seed: int


def run(job: Job) -> dict[str, float]:
    """One pointing trial; its movement time, endpoint error along the axis and hit."""
    from arteleop.operator import Expertise, TraitDistribution
    from arteleop.teleop.pointing import run_pointing_trial

    traits = TraitDistribution().draw(0, f"F{job.person:02d}", Expertise())
    r = run_pointing_trial(job.distance_m, job.width_m, traits, job.seed, job.lag_ms / 1000)
    return {"selected": float(r.selected), "movement_time_s": r.movement_time_s,
            "along_m": r.along_m, "hit": float(r.hit)}  # fmt: skip


def fit_line(x: np.ndarray, y: np.ndarray) -> tuple[float, float, float]:
    """(a, b, R^2) of y = a + b x."""
    b, a = np.polyfit(x, y, 1)
    r2 = 1 - np.sum((y - a - b * x) ** 2) / np.sum((y - y.mean()) ** 2)
    return float(a), float(b), float(r2)


def fit_lag_models(ids: np.ndarray, lags_s: np.ndarray, mt: np.ndarray) -> dict[str, dict]:
    """MacKenzie & Ware's additive and multiplicative models, least squares; coefficients and
    R^2."""
    out = {}
    designs = {
        "additive": np.column_stack([np.ones_like(ids), ids, lags_s]),
        "multiplicative": np.column_stack([np.ones_like(ids), ids, lags_s * ids]),
    }
    for name, X in designs.items():
        coef, *_ = np.linalg.lstsq(X, mt, rcond=None)
        r2 = 1 - np.sum((mt - X @ coef) ** 2) / np.sum((mt - mt.mean()) ** 2)
        out[name] = {"a_s": coef[0], "b_s_per_bit": coef[1], "c": coef[2], "r2": r2}
    return {k: {kk: float(vv) for kk, vv in v.items()} for k, v in out.items()}


def parse_lags(text: str) -> list[float]:
    try:
        lags = [float(x) for x in text.split(",") if x.strip()]
    except ValueError:
        lags = []
    if not lags or any(not np.isfinite(x) or x < 0 or x > 2000 for x in lags):
        raise argparse.ArgumentTypeError(
            f"{text!r}: give round-trip lags in ms, 0-2000, separated by commas (e.g. 0,75,150)"
        )
    return lags


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--people", type=int, default=10, help="simulated people (1 or more)")
    parser.add_argument(
        "--lags",
        type=parse_lags,
        default=[0.0, 75.0, 150.0, 225.0],
        help="round-trip lags (ms), comma-separated",
    )
    parser.add_argument(
        "--quick", action="store_true", help="4 people, the lags 0 and 225 ms: a few minutes"
    )
    parser.add_argument("--workers", type=int, default=len(os.sched_getaffinity(0)))
    parser.add_argument("--json", help="write the lag table and the fits to this file")
    args = parser.parse_args()
    if args.people < 1:
        parser.error(f"--people {args.people}: give 1 or more")
    if args.workers < 1:
        parser.error(f"--workers {args.workers}: give 1 or more")
    people, lags = (4, [0.0, 225.0]) if args.quick else (args.people, args.lags)
    jobs = [Job(p, d, w, lag, seed=1000 * p + 10 * i + j)
            for lag in lags for p in range(people)
            for i, d in enumerate(DISTANCES_M) for j, w in enumerate(WIDTHS_M)]  # fmt: skip
    t0 = time.perf_counter()
    with ProcessPoolExecutor(args.workers) as pool:
        rows = [dict(vars(job), **result) for job, result in zip(jobs, pool.map(run, jobs),
                                                                 strict=True)]  # fmt: skip
    print(f"{len(rows)} pointing trials, {people} people, in {time.perf_counter() - t0:.0f} s "
          f"on {args.workers} workers\n")  # fmt: skip
    report(rows, lags, args.json)


def report(rows: list[dict], lags: list[float], json_path: str | None) -> None:
    done = [r for r in rows if r["selected"]]
    missing = len(rows) - len(done)
    if missing:
        print(f"{missing} trials ended without a selection (timeout); left out\n")
    cells = []
    for lag in lags:
        for d in DISTANCES_M:
            for w in WIDTHS_M:
                c = [r for r in done if r["lag_ms"] == lag and r["distance_m"] == d
                     and r["width_m"] == w]  # fmt: skip
                if len(c) < 2:
                    continue
                along = np.array([r["along_m"] for r in c])
                we = 4.133 * along.std(ddof=1)
                de = d + along.mean()
                cells.append({
                    "lag_ms": lag, "D_m": d, "W_m": w, "n": len(c),
                    "id": float(np.log2(d / w + 1)), "id_e": float(np.log2(de / we + 1)),
                    "mt_s": float(np.mean([r["movement_time_s"] for r in c])),
                    "error_rate": float(1 - np.mean([r["hit"] for r in c])),
                    "we_mm": 1000 * we,
                })  # fmt: skip
    base = [c for c in cells if c["lag_ms"] == lags[0]]
    print(f"## Fitts' law through the loop, lag {lags[0]:g} ms (means over people)\n")
    print("| D (m) | W (mm) | ID (bits) | W_e (mm) | ID_e (bits) | MT (s) | errors |")
    print("| ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for c in base:
        print(f"| {c['D_m']:.1f} | {1000 * c['W_m']:.0f} | {c['id']:.2f} | {c['we_mm']:.1f} "
              f"| {c['id_e']:.2f} | {c['mt_s']:.2f} | {100 * c['error_rate']:.0f} % |")  # fmt: skip
    fits: dict[str, object] = {}
    if len(base) >= 3:
        a, b, r2 = fit_line(
            np.array([c["id_e"] for c in base]), np.array([c["mt_s"] for c in base])
        )
        a0, b0, r20 = fit_line(
            np.array([c["id"] for c in base]), np.array([c["mt_s"] for c in base])
        )
        fits["fitts_effective"] = {"a_s": a, "b_s_per_bit": b, "r2": r2}
        fits["fitts_nominal"] = {"a_s": a0, "b_s_per_bit": b0, "r2": r20}
        print(f"\nMT = {a:.2f} s + {b:.2f} s/bit x ID_e, R^2 = {r2:.2f} "
              f"(nominal ID: {a0:.2f} s + {b0:.2f} s/bit, R^2 = {r20:.2f})")  # fmt: skip
    per_lag = {"lag_ms": [], "movement_time_s": [], "error_rate": []}
    print("\n## Under added lag (round trip; means over all cells)\n")
    print("| lag (ms) | MT (s) | ratio to no lag | errors |")
    print("| ---: | ---: | ---: | ---: |")
    for lag in lags:
        c = [x for x in cells if x["lag_ms"] == lag]
        if not c:
            continue
        mt, err = (
            float(np.mean([x["mt_s"] for x in c])),
            float(np.mean([x["error_rate"] for x in c])),
        )
        per_lag["lag_ms"].append(lag)
        per_lag["movement_time_s"].append(mt)
        per_lag["error_rate"].append(err)
        print(
            f"| {lag:g} | {mt:.2f} | {mt / per_lag['movement_time_s'][0]:.2f} | {100 * err:.0f} % |"
        )
    if len(per_lag["lag_ms"]) > 1:
        ids = np.array([c["id"] for c in cells])
        lag_s = np.array([c["lag_ms"] / 1000 for c in cells])
        models = fit_lag_models(ids, lag_s, np.array([c["mt_s"] for c in cells]))
        fits.update(models)
        for name, m in models.items():
            print(f"\n{name}: a = {m['a_s']:.2f} s, b = {m['b_s_per_bit']:.2f} s/bit, "
                  f"c = {m['c']:.2f}, R^2 = {m['r2']:.3f}")  # fmt: skip
    if json_path:
        with open(json_path, "w", encoding="utf-8") as f:
            json.dump({**per_lag, "fits": fits, "cells": cells}, f, indent=1)
        print(f"\nwrote {json_path}")


if __name__ == "__main__":
    sys.exit(main())

"""A faster physics set-up against the default, on the study's trials: same outcome?

Runs the same synthetic trials (``--seeds`` per modality) with PyBullet's default 50 solver
iterations (the baseline) and with each of ``--iterations``, every set-up in a process of its
own, two at a time, one per core. Prints per set-up the outcomes, the median placement error,
how many trials end as the baseline's do, the physics' wall time per simulated second and the
loop's batch speed, then the medians per modality.

A set-up passes the speed issue's rule when every trial's outcome matches the baseline's and the
median placement errors differ by less than 1 mm.

    python benchmarks/bench_physics.py [--iterations 20,10] [--seeds 5]
"""

from __future__ import annotations

from arteleop import blas_kernel  # noqa: F401  (first: it picks numpy's BLAS kernel)

# isort: split
import argparse
import json
import os
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import replace
from pathlib import Path

import numpy as np

MODALITIES = ("none", "manipulation", "embodiment", "task", "full")
BASELINE = 50
RULE_MM = 1.0


def worker(iterations: int, seeds: int) -> None:
    """The trials with ``iterations`` solver iterations; one JSON line per trial."""
    from arteleop.scene import RemoteSite
    from arteleop.teleop import TrialConfig, run_trial, trial_operator

    for modality in MODALITIES:
        for seed in range(seeds):
            config = TrialConfig(modality=modality, seed=seed)
            config = replace(config, site=replace(config.site, solver_iterations=iterations))
            with RemoteSite(config.site) as site:
                source = trial_operator(site, config)
                t0 = time.perf_counter()
                result = run_trial(source, config, site)
                wall = time.perf_counter() - t0
            physics = next(s.latency_total_ms for s in result.stages if s.stage == "physics")
            print(json.dumps({
                "modality": modality, "seed": seed, "outcome": result.outcome.value,
                "placement_error_m": result.placement_error_m, "duration_s": result.duration_s,
                "wall_s": wall, "physics_ms": physics,
            }), flush=True)  # fmt: skip


def run(iterations: int, seeds: int, core: int) -> list[dict]:
    env = {**os.environ, "OMP_NUM_THREADS": "1"}
    command = [sys.executable, str(Path(__file__).resolve()), "--worker", str(iterations),
               "--seeds", str(seeds)]  # fmt: skip
    out = subprocess.run(
        command, env=env, capture_output=True, text=True,
        preexec_fn=lambda: os.sched_setaffinity(0, {core}),
    )  # fmt: skip
    if out.returncode != 0:
        sys.exit(f"{iterations} solver iterations: the trials failed\n{out.stderr[-2000:]}")
    return [json.loads(line) for line in out.stdout.splitlines() if line.startswith("{")]


def median_error_mm(rows: list[dict]) -> float:
    return 1000.0 * float(np.median([r["placement_error_m"] for r in rows
                                     if r["outcome"] == "success"]))  # fmt: skip


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--iterations", default="20,10", help="set-ups to compare with 50")
    parser.add_argument("--seeds", type=int, default=5)
    parser.add_argument("--worker", type=int, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.worker is not None:
        worker(args.worker, args.seeds)
        return
    try:
        setups = [BASELINE, *(int(v) for v in args.iterations.split(","))]
    except ValueError:
        parser.error(f"--iterations {args.iterations!r}: give whole numbers, e.g. 20,10")
    if min(setups) < 1 or args.seeds < 1:
        parser.error("--iterations and --seeds must be at least 1")
    cores = sorted(os.sched_getaffinity(0))
    with ThreadPoolExecutor(min(2, len(cores))) as pool:
        futures = [pool.submit(run, n, args.seeds, cores[i % len(cores)])
                   for i, n in enumerate(setups)]  # fmt: skip
        results = dict(zip(setups, (f.result() for f in futures), strict=True))

    base = results[BASELINE]
    print(f"## Physics set-ups on the study's trials ({args.seeds} seeds x 5 modalities)\n")
    print("Baseline: PyBullet's default, 50 solver iterations, run in the same invocation.\n")
    print("| solver iterations | successes | median placement error (mm) | vs 50 (mm) "
          "| outcome as with 50 | physics (ms per simulated s) | loop (x real time) "
          "| passes the rule |")  # fmt: skip
    print("| ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |")
    for n, rows in results.items():
        ok = sum(r["outcome"] == "success" for r in rows)
        same = sum(a["outcome"] == b["outcome"] for a, b in zip(rows, base, strict=True))
        delta = median_error_mm(rows) - median_error_mm(base)
        physics = np.median([r["physics_ms"] / r["duration_s"] for r in rows])
        speed = np.median([r["duration_s"] / r["wall_s"] for r in rows])
        passes = "baseline" if n == BASELINE else (
            "yes" if same == len(rows) and abs(delta) < RULE_MM else "no")  # fmt: skip
        print(f"| {n} | {ok}/{len(rows)} | {median_error_mm(rows):.1f} | {delta:+.1f} "
              f"| {same}/{len(rows)} | {physics:.1f} | {speed:.2f} | {passes} |")  # fmt: skip

    print("\n## Median placement error per modality (mm), successes only\n")
    print("| modality | " + " | ".join(f"{n} iterations" for n in results) + " |")
    print("| --- |" + " ---: |" * len(results))
    for modality in MODALITIES:
        cells = [median_error_mm([r for r in rows if r["modality"] == modality])
                 for rows in results.values()]  # fmt: skip
        print(f"| {modality} | " + " | ".join(f"{c:.1f}" for c in cells) + " |")


if __name__ == "__main__":
    main()

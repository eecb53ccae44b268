"""Batch speed of synthetic trials, this checkout against a baseline commit, side by side.

Runs the same trials (``--seeds`` per modality) in this checkout and in a git worktree of
``--baseline``, at the same time, each on a core of its own, so both see the same machine. Prints
per modality the median batch speed (simulated seconds per wall second) of each and their
ratio, and whether the trials' outcomes agree.

    python benchmarks/bench_speed.py --baseline 88190a3 [--seeds 5] [--modalities none,full]

The trials' numbers are not expected to equal the baseline's where the change alters the random
streams; the outcome column says how many trials end the same way.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent


def worker(modalities: list[str], seeds: int) -> None:
    """Run the trials with whichever ``arteleop`` is on the path; one JSON line per trial."""
    import arteleop
    from arteleop.scene import RemoteSite
    from arteleop.teleop import TrialConfig, run_trial, trial_operator

    print(json.dumps({"package": str(Path(arteleop.__file__).parent)}), flush=True)
    for modality in modalities:
        for seed in range(seeds):
            config = TrialConfig(modality=modality, seed=seed)
            with RemoteSite(config.site) as site:
                source = trial_operator(site, config)
                t0 = time.perf_counter()
                result = run_trial(source, config, site)
                wall = time.perf_counter() - t0
            row = result.to_row()
            print(json.dumps({
                "modality": modality, "seed": seed, "outcome": row["outcome"],
                "placement_error_m": row["placement_error_m"],
                "duration_s": result.duration_s, "wall_s": wall,
            }), flush=True)  # fmt: skip


def baseline_tree(ref: str) -> Path:
    """A worktree of ``ref`` beside the system's temporary files (made once, then reused)."""
    sha = subprocess.run(
        ["git", "-C", str(ROOT), "rev-parse", "--short", ref],
        check=True, capture_output=True, text=True,
    ).stdout.strip()  # fmt: skip
    tree = Path(os.environ.get("TMPDIR", "/tmp")) / f"arteleop-baseline-{sha}"
    if not tree.exists():
        subprocess.run(
            ["git", "-C", str(ROOT), "worktree", "add", "--detach", str(tree), sha],
            check=True, capture_output=True,
        )  # fmt: skip
    return tree


def launch(tree: Path, core: int, args: argparse.Namespace) -> subprocess.Popen[str]:
    env = {**os.environ, "PYTHONPATH": str(tree), "OMP_NUM_THREADS": "1"}
    command = [sys.executable, str(Path(__file__).resolve()), "--worker",
               "--seeds", str(args.seeds), "--modalities", args.modalities]  # fmt: skip
    return subprocess.Popen(
        command, cwd=tree, env=env, stdout=subprocess.PIPE, text=True,
        preexec_fn=lambda: os.sched_setaffinity(0, {core}),
    )  # fmt: skip


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--baseline", help="git commit to compare with, e.g. 88190a3")
    parser.add_argument("--seeds", type=int, default=5)
    parser.add_argument("--modalities", default="none,manipulation,embodiment,task,full")
    parser.add_argument("--worker", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.worker:
        worker(args.modalities.split(","), args.seeds)
        return
    if not args.baseline:
        parser.error("--baseline: give the commit to compare with, e.g. --baseline 88190a3")
    cores = sorted(os.sched_getaffinity(0))
    trees = {"this checkout": ROOT, f"baseline {args.baseline}": baseline_tree(args.baseline)}
    runs = {name: launch(tree, cores[i % len(cores)], args) for i, (name, tree) in
            enumerate(trees.items())}  # fmt: skip
    rows: dict[str, list[dict]] = {}
    for name, process in runs.items():
        out, _ = process.communicate()
        if process.returncode != 0:
            sys.exit(f"{name}: the trials failed (exit {process.returncode})")
        lines = [json.loads(line) for line in out.splitlines() if line.startswith("{")]
        print(f"{name}: arteleop from {lines[0]['package']}")
        rows[name] = lines[1:]
    new, old = rows.values()
    print(f"\n## Batch speed, one core each, {args.seeds} seeds per modality (x real time)\n")
    print(f"| modality | this checkout | baseline {args.baseline} | ratio | same outcome |")
    print("| --- | ---: | ---: | ---: | ---: |")
    for modality in args.modalities.split(","):
        a = [r for r in new if r["modality"] == modality]
        b = [r for r in old if r["modality"] == modality]
        speed_a = np.median([r["duration_s"] / r["wall_s"] for r in a])
        speed_b = np.median([r["duration_s"] / r["wall_s"] for r in b])
        same = sum(x["outcome"] == y["outcome"] for x, y in zip(a, b, strict=True))
        print(f"| {modality} | {speed_a:.2f} | {speed_b:.2f} | {speed_a / speed_b:.2f} "
              f"| {same}/{len(a)} |")  # fmt: skip
    total = {k: sum(r["duration_s"] for r in v) / sum(r["wall_s"] for r in v)
             for k, v in (("new", new), ("old", old))}  # fmt: skip
    print(f"\nAll trials: {total['new']:.2f}x against {total['old']:.2f}x real time "
          f"(ratio {total['new'] / total['old']:.2f}).")  # fmt: skip
    errors = {k: np.median([r["placement_error_m"] for r in v if r["outcome"] == "success"])
              for k, v in (("new", new), ("old", old))}  # fmt: skip
    print(f"Median placement error of the successes: {errors['new'] * 1000:.1f} mm against "
          f"{errors['old'] * 1000:.1f} mm.")  # fmt: skip


if __name__ == "__main__":
    main()

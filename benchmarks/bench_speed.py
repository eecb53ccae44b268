"""Batch speed of synthetic trials, this checkout against a baseline commit, side by side.

Runs the same trials (``--seeds`` per modality) in this checkout and in a git worktree of
``--baseline``, at the same time, each on a core of its own, so both see the same machine; the
cores are swapped half-way through the seeds, since one core may be slower than the other (here
an identical checkout ran 12 % slower on the first). ``--baseline HEAD`` on a clean checkout
measures that noise: its ratios should be 1.00. Prints
per modality the median batch speed (simulated seconds per wall second) of each and their
ratio, and whether the trials' outcomes agree.

The second baseline is PyBullet alone: each of this checkout's trials is replayed on a fresh
site from the arm and gripper commands it sent, step for step, with nothing else running (no
operator, IK, camera or tracker). That is the physics' own speed, the ceiling of the loop's;
the replay must end with the bowl where the trial left it, to the bit. The last table is where
a simulated second goes in this checkout, by stage of the loop.

    python benchmarks/bench_speed.py --baseline 88190a3 [--seeds 5] [--modalities none,full]

The trials' numbers are not expected to equal the baseline's where the change alters the random
streams; the outcome column says how many trials end the same way, the identical column how
many end with the same outcome, time and placement error to the bit.
"""

from __future__ import annotations

import arteleop  # first: it picks numpy's BLAS kernel (arteleop/blas_kernel.py)

# isort: split
import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
IDENTITY = ("outcome", "duration_s", "placement_error_m")
NESTED = ("ik", "mapping")


def worker(modalities: list[str], seeds: range, replay: bool) -> None:
    """Run the trials with whichever ``arteleop`` is on the path; one JSON line per trial.

    Both sides record their commands, so that their timed trials do the same work; the side
    that replays them does so after its last trial, not between trials (replaying between
    them made an identical checkout look 13 % slower than itself).
    """
    from arteleop.scene import RemoteSite
    from arteleop.teleop import TrialConfig, run_trial, trial_operator

    print(json.dumps({"package": str(Path(arteleop.__file__).parent)}), flush=True)
    done = []
    for modality in modalities:
        for seed in seeds:
            config = TrialConfig(modality=modality, seed=seed)
            with RemoteSite(config.site) as site:
                source = trial_operator(site, config)
                commands = record_commands(site)
                t0 = time.perf_counter()
                result = run_trial(source, config, site)
                wall = time.perf_counter() - t0
                bowl = site.observe(links=()).T_base_bowl
            row = result.to_row()
            line = {
                "modality": modality, "seed": seed, "outcome": row["outcome"],
                "placement_error_m": row["placement_error_m"],
                "duration_s": result.duration_s, "wall_s": wall,
                "stages_ms": {s.stage: s.latency_total_ms for s in result.stages},
            }  # fmt: skip
            done.append((line, config, commands if replay else None, bowl))
    for line, config, commands, bowl in done:
        if commands is not None:
            with RemoteSite(config.site) as fresh:
                line["replay_wall_s"] = replay_commands(fresh, commands)
                line["replay_same"] = bool(
                    np.array_equal(fresh.observe(links=()).T_base_bowl, bowl)
                )
        print(json.dumps(line), flush=True)


def record_commands(site: object) -> list[object]:
    """Every command and physics step the trial gives ``site``, in order (None: one step)."""
    events: list[object] = []
    apply, step = site.apply, site.step

    def recorded_apply(command: object) -> None:
        events.append(command)
        apply(command)

    def recorded_step(n: int = 1) -> None:
        events.extend([None] * n)
        step(n)

    site.apply, site.step = recorded_apply, recorded_step
    return events


def replay_commands(site: object, events: list[object]) -> float:
    """Give a fresh site the same commands and steps; the wall time it takes (s)."""
    apply, step = site.apply, site.step
    t0 = time.perf_counter()
    for event in events:
        if event is None:
            step()
        else:
            apply(event)
    return time.perf_counter() - t0


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


def launch(
    tree: Path, core: int, args: argparse.Namespace, seeds: range, replay: bool
) -> subprocess.Popen[str]:
    env = {**os.environ, "PYTHONPATH": str(tree), "OMP_NUM_THREADS": "1"}
    command = [sys.executable, str(Path(__file__).resolve()), "--worker",
               "--first-seed", str(seeds.start), "--seeds", str(len(seeds)),
               "--modalities", args.modalities]  # fmt: skip
    if replay:
        command.append("--replay")
    return subprocess.Popen(
        command, cwd=tree, env=env, stdout=subprocess.PIPE, text=True,
        preexec_fn=lambda: os.sched_setaffinity(0, {core}),
    )  # fmt: skip


def run_side_by_side(trees: dict[str, Path], args: argparse.Namespace) -> dict[str, list[dict]]:
    """Each tree's trials, on a core of its own at the same time; the first half of the seeds
    with the checkout on the first core, the second half with the cores swapped (one core of
    this machine ran the same code 12 % slower than the other)."""
    cores = sorted(os.sched_getaffinity(0))
    half = (args.seeds + 1) // 2
    rows: dict[str, list[dict]] = {name: [] for name in trees}
    for swap, seeds in enumerate((range(half), range(half, args.seeds))):
        if not seeds:
            continue
        runs = {
            name: launch(tree, cores[(i + swap) % len(cores)], args, seeds, replay=i == 0)
            for i, (name, tree) in enumerate(trees.items())
        }
        for name, process in runs.items():
            out, _ = process.communicate()
            if process.returncode != 0:
                sys.exit(f"{name}: the trials failed (exit {process.returncode})")
            lines = [json.loads(line) for line in out.splitlines() if line.startswith("{")]
            if not swap:
                print(f"{name}: arteleop from {lines[0]['package']}")
            rows[name] += lines[1:]
    order = args.modalities.split(",")
    for lines in rows.values():
        lines.sort(key=lambda r: (order.index(r["modality"]), r["seed"]))
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--baseline", help="git commit to compare with, e.g. 88190a3")
    parser.add_argument("--seeds", type=int, default=5)
    parser.add_argument("--first-seed", type=int, default=0, help=argparse.SUPPRESS)
    parser.add_argument("--modalities", default="none,manipulation,embodiment,task,full")
    parser.add_argument("--worker", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--replay", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.worker:
        seeds = range(args.first_seed, args.first_seed + args.seeds)
        worker(args.modalities.split(","), seeds, args.replay)
        return
    if not args.baseline:
        parser.error("--baseline: give the commit to compare with, e.g. --baseline 88190a3")
    trees = {"this checkout": ROOT, f"baseline {args.baseline}": baseline_tree(args.baseline)}
    rows = run_side_by_side(trees, args)
    new, old = rows.values()
    print(f"\n## Batch speed, one core each, {args.seeds} seeds per modality (x real time)\n")
    print(f"| modality | this checkout | baseline {args.baseline} | ratio | PyBullet alone "
          "| same outcome | identical |")  # fmt: skip
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: |")
    for modality in args.modalities.split(","):
        a = [r for r in new if r["modality"] == modality]
        b = [r for r in old if r["modality"] == modality]
        speed_a = np.median([r["duration_s"] / r["wall_s"] for r in a])
        speed_b = np.median([r["duration_s"] / r["wall_s"] for r in b])
        physics = np.median([r["duration_s"] / r["replay_wall_s"] for r in a])
        same = sum(x["outcome"] == y["outcome"] for x, y in zip(a, b, strict=True))
        identical = sum(
            all(x[k] == y[k] or (x[k] != x[k] and y[k] != y[k]) for k in IDENTITY)
            for x, y in zip(a, b, strict=True)
        )
        print(f"| {modality} | {speed_a:.2f} | {speed_b:.2f} | {speed_a / speed_b:.2f} "
              f"| {physics:.1f} | {same}/{len(a)} | {identical}/{len(a)} |")  # fmt: skip
    total = {k: sum(r["duration_s"] for r in v) / sum(r["wall_s"] for r in v)
             for k, v in (("new", new), ("old", old))}  # fmt: skip
    print(f"\nAll trials: {total['new']:.2f}x against {total['old']:.2f}x real time "
          f"(ratio {total['new'] / total['old']:.2f}).")  # fmt: skip
    errors = {k: np.median([r["placement_error_m"] for r in v if r["outcome"] == "success"])
              for k, v in (("new", new), ("old", old))}  # fmt: skip
    print(f"Median placement error of the successes: {errors['new'] * 1000:.1f} mm against "
          f"{errors['old'] * 1000:.1f} mm.")  # fmt: skip
    replayed = sum(r["replay_same"] for r in new)
    print(f"Replays that end with the bowl where the trial left it: {replayed}/{len(new)}.")
    print_budget(new)


def print_budget(rows: list[dict]) -> None:
    """Where a simulated second goes in this checkout: wall ms per simulated second by stage,
    medians over the trials; the rest is the loop's own (clock, snapshots, monitor)."""
    per_s = [{k: v / r["duration_s"] for k, v in r["stages_ms"].items()} for r in rows]
    for r, d in zip(rows, per_s, strict=True):
        d["physics alone (replay)"] = 1000.0 * r["replay_wall_s"] / r["duration_s"]
        # "ik" and "mapping" are parts of "control_tick"; the rest is outside every stage.
        timed = sum(v for k, v in r["stages_ms"].items() if k not in NESTED)
        d["untimed"] = (1000.0 * r["wall_s"] - timed) / r["duration_s"]
        d["whole loop"] = 1000.0 * r["wall_s"] / r["duration_s"]
    print("\n## Where a simulated second goes (this checkout, wall ms per simulated second)\n")
    print("| stage | median | share of the loop |")
    print("| --- | ---: | ---: |")
    whole = np.median([d["whole loop"] for d in per_s])
    for stage in sorted(per_s[0], key=lambda k: -np.median([d.get(k, 0.0) for d in per_s])):
        ms = np.median([d.get(stage, 0.0) for d in per_s])
        print(f"| {stage} | {ms:.1f} | {ms / whole:.0%} |")
    # The machine's speed changes by up to 1.7x from one hour to the next; this ratio does not.
    alone = np.median([d["physics alone (replay)"] for d in per_s])
    print(
        f"\nLoop to PyBullet alone (medians): {alone / whole:.2f}; the loop's own work costs "
        f"{(whole - alone) / alone:.1f} times the physics."
    )


if __name__ == "__main__":
    main()

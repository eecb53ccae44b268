"""Fingerprints of five seeded synthetic trials: a change that only reorganises code must leave
every one of them the same to the bit.

Each line is a trial (modality and seed), the SHA-256 of its trace (every control tick's row of
``TRACE_COLUMNS``, as float64 bytes, the first 16 hex digits), its outcome, duration and placement
error. Run it before and after a change and compare the two outputs; ``--baseline COMMIT`` runs
the same trials in a git worktree of that commit after this checkout's and says, per trial,
whether the two agree.

    python benchmarks/trace_hashes.py [--baseline COMMIT]
"""

from __future__ import annotations

import arteleop  # first: it picks numpy's BLAS kernel (arteleop/blas_kernel.py)

# isort: split
import argparse
import hashlib
import json
import subprocess
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
TRIALS = (("none", 0), ("full", 0), ("task", 1), ("manipulation", 2), ("embodiment", 3))


def fingerprints() -> list[dict[str, object]]:
    """The five trials with whichever ``arteleop`` is imported."""
    from arteleop.scene import RemoteSite
    from arteleop.teleop import TRACE_COLUMNS, TrialConfig, run_trial, trial_operator

    rows = []
    for modality, seed in TRIALS:
        config = TrialConfig(modality=modality, seed=seed, record_trace=True)
        with RemoteSite(config.site) as site:
            result = run_trial(trial_operator(site, config), config, site)
        assert result.trace is not None
        table = np.stack([result.trace[c] for c in TRACE_COLUMNS], axis=1)
        rows.append({
            "trial": f"{modality}{seed}",
            "hash": hashlib.sha256(np.ascontiguousarray(table).tobytes()).hexdigest()[:16],
            "outcome": result.outcome.value,
            "duration_s": result.duration_s,
            "placement_error_mm": 1000 * result.to_row()["placement_error_m"],
        })  # fmt: skip
    return rows


def baseline(commit: str) -> list[dict[str, object]]:
    """The same trials in a worktree of ``commit``, in a process of its own."""
    sha = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", commit],
                         check=True, capture_output=True, text=True).stdout.strip()  # fmt: skip
    tree = Path("/tmp") / f"arteleop-hashes-{sha}"
    if not tree.exists():
        subprocess.run(["git", "-C", str(ROOT), "worktree", "add", "--detach", str(tree), sha],
                       check=True, capture_output=True)  # fmt: skip
    code = (
        "import sys; sys.path.insert(0, sys.argv[1]); import arteleop, json; "
        "sys.path.insert(0, sys.argv[2]); import trace_hashes as t; "
        "print(json.dumps(t.fingerprints()))"
    )
    out = subprocess.run(
        [sys.executable, "-c", code, str(tree), str(ROOT / "benchmarks")],
        check=True, capture_output=True, text=True, cwd=tree,
    ).stdout  # fmt: skip
    return json.loads(out.strip().splitlines()[-1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--baseline", help="a commit to compare with, trial by trial")
    args = parser.parse_args()
    here = fingerprints()
    print(f"arteleop {arteleop.__version__} from {Path(arteleop.__file__).parent}")
    other = baseline(args.baseline) if args.baseline else None
    head = "| trial | hash | outcome | duration (s) | error (mm) |"
    print(head + (f" {args.baseline} | same |" if other else ""))
    print("| --- " * (5 + 2 * bool(other)) + "|")
    for k, row in enumerate(here):
        line = (f"| {row['trial']} | {row['hash']} | {row['outcome']} | {row['duration_s']:.2f} "
                f"| {row['placement_error_mm']:.2f} |")  # fmt: skip
        if other:
            line += f" {other[k]['hash']} | {'yes' if other[k]['hash'] == row['hash'] else 'NO'} |"
        print(line)


if __name__ == "__main__":
    main()

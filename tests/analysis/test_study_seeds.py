"""benchmarks/study_seeds.py: the default study's answer pooled over cohorts, on run folders
with known effects."""

from __future__ import annotations

import importlib.util
import re
from pathlib import Path

import numpy as np

from tests.analysis.make_study import TIME_S, make_run

_SPEC = importlib.util.spec_from_file_location(
    "study_seeds", Path(__file__).parents[2] / "benchmarks" / "study_seeds.py"
)
assert _SPEC is not None and _SPEC.loader is not None
study_seeds = importlib.util.module_from_spec(_SPEC)
_SPEC.loader.exec_module(study_seeds)


def test_the_pooled_effect_recovers_the_known_one(tmp_path: Path, capsys) -> None:
    runs = [make_run(tmp_path / f"run{k}", seed=k, trajectories=False) for k in (1, 2)]
    assert study_seeds.main([str(r) for r in runs]) == 0
    out = capsys.readouterr().out
    row = re.search(r"\| full \| time \| (\d+) \| x ([\d.]+) \| ([\d.]+) to ([\d.]+) \| (\w+)", out)
    assert row is not None
    pairs, low, high = int(row.group(1)), float(row.group(3)), float(row.group(4))
    # Each run's last participant failed under full: 21 pairs a run. Non-experts' true ratio is
    # 26/45; the 7 experts' none is 0.8 times theirs: a geometric mean of 0.62 over a cohort.
    assert pairs == 42
    truth = np.exp((15 * np.log(TIME_S["full"] / TIME_S["none"])
                    + 7 * np.log(TIME_S["full"] / (0.8 * TIME_S["none"]))) / 22)  # fmt: skip
    assert low < truth < high and row.group(5) == "lower"
    assert "| 2 | full | 21/22 |" in out


def test_a_missing_run_is_named(tmp_path: Path, capsys) -> None:
    assert study_seeds.main([str(tmp_path / "nope")]) == 2
    assert capsys.readouterr().err == (
        f"study_seeds: {tmp_path / 'nope'}: no such file; a run folder holds trials.csv\n"
    )

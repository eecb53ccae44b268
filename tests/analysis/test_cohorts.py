"""'arteleop analyze' over several run folders: a design's answer pooled over its cohorts, on
run folders with known effects."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from arteleop.cli import main
from tests.analysis.make_study import TIME_S, make_run


def test_the_pooled_effect_recovers_the_known_one(tmp_path: Path, capsys) -> None:
    runs = [make_run(tmp_path / f"run{k}", seed=k, trajectories=False) for k in (1, 2)]
    out_dir = tmp_path / "pooled"
    assert main(["analyze", *map(str, runs), "--out", str(out_dir)]) == 0
    out = capsys.readouterr().out
    pattern = r"\| 0ms \| full \| time \| (\d+) \| x ([\d.]+) \| ([\d.]+) to ([\d.]+) \| (\w+)"
    row = re.search(pattern, out)
    assert row is not None, out
    pairs, low, high = int(row.group(1)), float(row.group(3)), float(row.group(4))
    # Each run's last participant failed under full: 21 pairs a run. Non-experts' true ratio is
    # 26/45; the 7 experts' none is 0.8 times theirs: a geometric mean of 0.62 over a cohort.
    assert pairs == 42
    truth = np.exp((15 * np.log(TIME_S["full"] / TIME_S["none"])
                    + 7 * np.log(TIME_S["full"] / (0.8 * TIME_S["none"]))) / 22)  # fmt: skip
    assert low < truth < high and row.group(5) == "lower"
    assert "| 2 | 0ms | full | 21/22 |" in out
    effects = pd.read_csv(out_dir / "pooled_effects.csv")
    full_time = effects[(effects["modality"] == "full") & (effects["measure"] == "time")]
    assert full_time["pairs"].tolist() == [42]
    assert sorted(p.name for p in out_dir.iterdir()) == [
        "cohort_medians.csv",
        "cohorts.md",
        "experts.csv",
        "pooled_effects.csv",
    ]


def test_cohorts_without_a_success_are_reported(tmp_path: Path, capsys) -> None:
    """A pilot whose trials all timed out: tables of no success, not a traceback; analysed
    alone, the trials left out are said."""
    runs = [make_run(tmp_path / f"run{k}", seed=k, n=8, trajectories=False) for k in (1, 2)]
    for run in runs:
        trials = pd.read_csv(run / "trials.csv")
        trials["outcome"] = "timeout"
        trials.to_csv(run / "trials.csv", index=False)
    assert main(["analyze", *map(str, runs), "--out", str(tmp_path / "pooled")]) == 0
    out = capsys.readouterr().out
    assert "| 1 | 0ms | full | 0/8 |" in out
    experts = pd.read_csv(tmp_path / "pooled" / "experts.csv")
    assert experts.empty and list(experts.columns) == [
        "network",
        "modality",
        "experts_s",
        "others_s",
        "gap_s",
    ]
    assert main(["analyze", str(runs[0]), "--out", str(tmp_path / "one")]) == 0
    assert capsys.readouterr().out.startswith(
        "analysed 0 successful experimental trials of 0 participants; left out: timeout 40\n"
    )


def test_a_missing_run_is_named(tmp_path: Path, capsys) -> None:
    run = make_run(tmp_path / "run", trajectories=False)
    assert main(["analyze", str(run), str(tmp_path / "nope"), "--out", str(tmp_path / "r")]) == 2
    assert capsys.readouterr().err == (
        f"arteleop: error: {tmp_path / 'nope'}: no such file; a run folder holds trials.csv\n"
    )
    assert not (tmp_path / "r").exists()


@pytest.mark.parametrize(
    ("args", "message"),
    [
        ([], "arteleop analyze needs a run folder or a trials CSV: 'arteleop analyze my-run "
             "--out my-report'; several run folders of one design are pooled."),
        (["a", "b", "--participants", "p.csv"],
         "--participants goes with one bare trials CSV; pooled run folders each bring their "
         "own participants.csv."),
        (["run", "a/../run"], "a/../run is given twice (as run): each cohort is pooled once."),
    ],
)  # fmt: skip
def test_what_pooling_cannot_take_is_refused(args: list[str], message: str, capsys) -> None:
    assert main(["analyze", *args]) == 2
    assert capsys.readouterr().err == f"arteleop: error: {message}\n"

"""'arteleop analyze' over several run folders: a design's answer pooled over its cohorts, on
run folders with known effects."""

from __future__ import annotations

import re
import shutil
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


def test_a_pointing_run_with_no_trial_yet_says_so(tmp_path: Path, capsys) -> None:
    # A served pointing study before its first trial ends: it was "trials.csv: no such file".
    (served := tmp_path / "served").mkdir()
    (served / "manifest.json").write_text('{"task": "pointing", "cohort": "real"}')
    assert main(["analyze", str(served), "--out", str(tmp_path / "r")]) == 2
    assert capsys.readouterr().err == (
        f"arteleop: error: {served}: a pointing study with no trial ended yet: its pointing.csv "
        "is written as its trials end (a simulated run's once every block is in)\n"
    )


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


# Pooling that checks: no cohort twice, one design --------------------------------------------

STUDY = 'name = "{name}"\nseed = {seed}\ntimeout_s = {timeout}\n[cohort]\nsize = {size}\n'


def _refusal(args: list[str], capsys) -> str:
    assert main(["analyze", *args]) == 2
    return capsys.readouterr().err


def test_a_cohort_is_not_pooled_twice(tmp_path: Path, capsys) -> None:
    run = make_run(tmp_path / "run", seed=1, trajectories=False)
    make_run(tmp_path / "again", seed=1, trajectories=False)  # forgot --seed
    shutil.copytree(run, tmp_path / "backup")
    for copy in ("again", "backup"):
        assert _refusal([str(run), str(tmp_path / copy), "--out", str(tmp_path / "r")], capsys) == (
            f"arteleop: error: {tmp_path / copy} repeats {run}'s trials row for row for 22 "
            "participant(s) (P01, P02, P03, ...): a copy of the folder, or one run twice. Each "
            "participant may count once: leave one of them out\n"
        )
    # Run twice with one seed where the numbers still differ (another machine's rounding).
    other = make_run(tmp_path / "other", seed=2, trajectories=False)
    for folder in (run, other):
        (folder / "manifest.json").write_text('{"seed": 7, "plan_sha256": "ab12"}')
    assert _refusal([str(run), str(other)], capsys) == (
        f"arteleop: error: {run} and {other} are one cohort run twice (seed 7, the same plan): "
        "the same simulated participants would count twice. Pool runs of other seeds "
        "(arteleop study run FILE --seed N)\n"
    )
    assert not (tmp_path / "r").exists()
    # People served one plan twice are two cohorts.
    (other / "manifest.json").write_text('{"seed": 7, "plan_sha256": "ab12", "cohort": "real"}')
    assert main(["analyze", str(run), str(other), "--out", str(tmp_path / "r")]) == 0


def test_cohorts_of_other_designs_are_pooled_only_when_asked(tmp_path: Path, capsys) -> None:
    a, b = (make_run(tmp_path / f"run{k}", seed=k, n=8, trajectories=False) for k in (1, 2))
    (a / "study.toml").write_text(STUDY.format(name="pilot", seed=1, timeout=120.0, size=8))
    # Seed, size and name are not the design: pooled without a word.
    (b / "study.toml").write_text(STUDY.format(name="main", seed=2, timeout=120, size=20))
    assert main(["analyze", str(a), str(b), "--out", str(tmp_path / "same")]) == 0
    assert "note:" not in capsys.readouterr().out
    (b / "study.toml").write_text(STUDY.format(name="main", seed=2, timeout=60.0, size=20))
    said = f"timeout_s (120.0 in {a}, 60.0 here)"
    assert _refusal([str(a), str(b), "--out", str(tmp_path / "r")], capsys) == (
        f"arteleop: error: {b / 'study.toml'}: not the design of {a}: {said}. Cohorts pooled "
        "must differ only in seed and size; give --allow-different-designs to compare the "
        "designs deliberately\n"
    )
    out_dir = tmp_path / "compared"
    args = [str(a), str(b), "--out", str(out_dir), "--allow-different-designs"]
    assert main(["analyze", *args]) == 0
    note = f"Different designs, compared deliberately: {b} differs from {a} in {said}."
    assert f"note: {note}\n" in capsys.readouterr().out
    report = (out_dir / "cohorts.md").read_text()
    assert report.startswith("# 2 cohorts of different designs\n") and f"**{note}**" in report
    (b / "study.toml").unlink()
    assert main(["analyze", str(a), str(b), "--out", str(out_dir), "--force"]) == 0
    assert f"note: Designs not checked: no study.toml in {b}.\n" in capsys.readouterr().out
    (b / "study.toml").write_text("timeout_s = [")
    assert _refusal([str(a), str(b), "--out", str(out_dir), "--force"], capsys) == (
        f"arteleop: error: {b / 'study.toml'}: not a study file (Invalid value (at end of "
        "document))\n"
    )


def test_a_sensitivity_run_is_said_so_and_pooled_with_the_models_only_when_asked(
    tmp_path: Path, capsys
) -> None:
    model, changed = (make_run(tmp_path / f"run{k}", seed=k, n=8, trajectories=False)
                      for k in (1, 2))  # fmt: skip
    (model / "study.toml").write_text(STUDY.format(name="s", seed=1, timeout=120.0, size=8))
    (changed / "study.toml").write_text(
        STUDY.format(name="s", seed=2, timeout=120.0, size=8)
        + "[operator_params]\nmax_look_s = 3.0  # the model's: 1.5\n"
    )
    said = f"operator_params.max_look_s (missing in {model}, 3.0 here)"
    assert _refusal([str(model), str(changed), "--out", str(tmp_path / "r")], capsys) == (
        f"arteleop: error: {changed / 'study.toml'}: not the design of {model}: {said}. Cohorts "
        "pooled must differ only in seed and size; give --allow-different-designs to compare "
        "the designs deliberately\n"
    )
    note = (f"A sensitivity run: the simulated participants of {changed} have constants changed "
            "from the model's (max_look_s = 3.0; study.toml's [operator_params]).")  # fmt: skip
    args = [str(model), str(changed), "--out", str(tmp_path / "r"), "--allow-different-designs"]
    assert main(["analyze", *args]) == 0
    assert f"note: {note}\n" in capsys.readouterr().out
    assert main(["analyze", str(changed), "--out", str(tmp_path / "one")]) == 0
    assert f"note: {note}\n" in capsys.readouterr().out
    assert f"- {note}" in (tmp_path / "one" / "report.md").read_text()
    assert main(["analyze", str(model), "--out", str(tmp_path / "model")]) == 0
    assert "A sensitivity run" not in capsys.readouterr().out
    # Cohorts of one sensitivity run: one note for them all.
    again = make_run(tmp_path / "run3", seed=3, n=8, trajectories=False)
    shutil.copy(changed / "study.toml", again / "study.toml")
    assert main(["analyze", str(changed), str(again), "--out", str(tmp_path / "both")]) == 0
    notes = [line for line in capsys.readouterr().out.splitlines() if line.startswith("note:")]
    assert notes == [f"note: A sensitivity run: the simulated participants of {changed}, {again} "
                     "have constants changed from the model's (max_look_s = 3.0; study.toml's "
                     "[operator_params])."]  # fmt: skip

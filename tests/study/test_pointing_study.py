"""A pointing study run from a study file: the design, its trials, the run folder and its
report; the definition's bad values refused at their line."""

from __future__ import annotations

import csv
import json
from dataclasses import replace
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from arteleop.analysis.pointing import pointing_table_path
from arteleop.cli import main
from arteleop.errors import StudyDefinitionError
from arteleop.operator import OperatorParams
from arteleop.scene import SiteConfig
from arteleop.study import RunComplete, parse_study, resume_study, run_study
from arteleop.study.pointing_design import PointingDesign
from arteleop.study.pointing_run import BLOCKS_DIR, pointing_blocks
from arteleop.study.pointing_session import ServedPointingRun
from arteleop.study.protocol import operator_traits
from arteleop.study.session import served_run
from arteleop.study.session_words import consent_text
from arteleop.teleop import POINTING, Outcome, PointingMonitor, trial_task
from arteleop.teleop.pointing import run_pointing_trial

TINY = """\
task = "pointing"
seed = 0
participants = [{id = "F02"}]

[pointing]
distances_m = [0.1]
widths_m = [0.03]
repetitions = 2

[[conditions]]
cues = []
round_trip_ms = 150

[[conditions]]
cues = []
round_trip_ms = 0
"""


def test_a_pointing_study_runs_each_trial_as_the_pointing_trial_and_keeps_what_a_stop_left(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Each row of pointing.csv is the pointing trial of its seed, by the participant's traits,
    under its block's lag, bringing the belief and the outcome the trial before left. Stopped
    after its first block (each in a worker process of its own), the run keeps that block, and
    resume runs the other; the report is the pointing analysis; a finished run has nothing to
    resume; the run's study.toml is the study."""
    study = parse_study(TINY)

    def stop(*_: object) -> None:
        raise KeyboardInterrupt

    out = tmp_path / "run"
    with pytest.raises(KeyboardInterrupt):
        run_study(study, out, workers=1, progress=stop)
    assert [p.name for p in (out / BLOCKS_DIR).iterdir()] == ["block-00001.csv"]
    assert not (out / "pointing.csv").exists()
    cut = out / BLOCKS_DIR / "block-00002.csv"  # a block file not whole: that block runs again
    cut.write_text("participant,round_trip_ms\nF02,0.0\n")
    assert main(["study", "resume", str(out), "--workers", "1", "--quiet"]) == 0
    printed = capsys.readouterr().out
    assert printed.startswith(f"4 pointing trials in {out} (2 run now)\nlag (ms)"), printed
    assert f"note: {cut}: not the rows of participant F02's block 2" in printed
    assert not (out / BLOCKS_DIR).exists()
    with open(out / "pointing.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    # Study seed 0: bench_fitts's seeds, 10000 x the participant's place + 100 x rep + cell;
    # the Williams square's first order of the lags.
    assert [(r["participant"], r["block"], r["trial"], r["seed"], r["round_trip_ms"])
            for r in rows] == [
        ("F02", "1", "1", "0", "150.0"), ("F02", "1", "2", "100", "150.0"),
        ("F02", "2", "3", "0", "0.0"), ("F02", "2", "4", "100", "0.0"),
    ]  # fmt: skip
    traits = operator_traits(study, study.participants[0])
    fresh = OperatorParams()
    first = run_pointing_trial(0.1, 0.03, traits, 0, 0.15, 40.0, fresh)
    carried = replace(fresh, familiar_lag_s=first.believed_lag_s,
                      seen_outcomes=fresh.seen_outcomes.after(not first.hit))  # fmt: skip
    second = run_pointing_trial(0.1, 0.03, traits, 100, 0.15, 40.0, carried)
    for row, trial in zip(rows[:2], (first, second), strict=True):
        assert float(row["movement_time_s"]) == trial.movement_time_s
        assert (float(row["along_m"]), float(row["across_m"])) == (trial.along_m, trial.across_m)
        assert float(row["hit"]) == float(trial.hit)
    manifest = json.loads((out / "manifest.json").read_text())
    assert manifest["task"] == "pointing"
    (resumed,) = manifest["resumed"]  # resumed once, with the first block's two trials in
    assert resumed["trials_in"] == 2 and resumed["numpy_loops"] == manifest["numpy_loops"]
    assert parse_study((out / "study.toml").read_text()) == study
    assert "## Lag 150 ms (round trip)" in (out / "report" / "report.md").read_text()
    with pytest.raises(RunComplete, match="is complete"):
        resume_study(out)


def test_a_block_is_every_cell_per_repetition_in_an_order_of_its_own() -> None:
    """Study seed 0 keeps bench_fitts's seeds and orders; another seed gives others."""
    design = PointingDesign((0.1, 0.2), (0.01, 0.02, 0.04), 3)
    block = design.block(3)
    cells = [(i, j) for i in range(2) for j in range(3)]
    for rep in range(3):
        order = np.random.default_rng([3, rep]).permutation(6)
        trials = block[6 * rep : 6 * rep + 6]
        assert [t.seed for t in trials] == [30000 + 100 * rep + 10 * cells[k][0] + cells[k][1]
                                            for k in order]  # fmt: skip
        assert [(t.distance_m, t.width_m) for t in trials] == [
            (design.distances_m[cells[k][0]], design.widths_m[cells[k][1]]) for k in order
        ]
    other = design.block(3, study_seed=1)
    assert sorted((t.distance_m, t.width_m) for t in other) == sorted(
        (t.distance_m, t.width_m) for t in block
    )
    assert not {t.seed for t in other} & {t.seed for t in block}
    assert trial_task("pointing") is POINTING
    assert type(POINTING.monitor(SiteConfig().workspace)) is PointingMonitor


CONDITION = "\n[[conditions]]\ncues = []\nround_trip_ms = 0\n"
UNUSED = (
    "a pointing study does not use it (its trials are the [pointing] table's, without practice, "
    "on the default camera and hand filter, and it is not served to people); remove it."
)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ('task = "pointing"\n',
         'study.toml line 1: task = "pointing": give its lags as [[conditions]] tables, one '
         "round_trip_ms each (cues = [] for all), e.g. round_trip_ms = 0 and round_trip_ms = 225."),
        ('task = "pointing"\n[[conditions]]\ncues = ["full"]\n',
         "study.toml: conditions: condition 1 (full@0ms): a pointing study's conditions are "
         "lags; give cues = [], jitter_ms = 0 and loss = 0, and round_trip_ms."),
        ("seed = 1\n[pointing]\nrepetitions = 3\n",
         'study.toml: pointing: the [pointing] table designs a pointing study; give task = '
         "\"pointing\" with it (task is 'pick-and-place'), or remove the table."),
        ('task = "pointing"\n[pointing]\nrepetitions = 1\n' + CONDITION,
         "study.toml line 3: pointing.repetitions = 1: expected 2 to 99 (an effective width "
         "needs a spread)."),
        ('task = "pointing"\n[pointing]\ndistances_m = [0.1, 0.6]\n' + CONDITION,
         "study.toml line 3: pointing.distances_m = [0.1, 0.6]: expected 1 to 9 different "
         "values, each 0.02-0.4 m."),
        ('task = "pointing"\n[pointing]\nwidths_m = [0.02, 0.02]\n' + CONDITION,
         "study.toml line 3: pointing.widths_m = [0.02, 0.02]: expected 1 to 9 different "
         "values, each 0.005-0.1 m."),
        ('task = "pointing"\n[pointing]\ndistances_m = [0.05]\nwidths_m = [0.06]\n' + CONDITION,
         "study.toml line 4: pointing.widths_m = [0.06]: each target must be narrower than "
         "the shortest distance (0.05 m), or it covers the start."),
        ('task = "pointing"\nstart_xy_m = [0.6, -0.4]\n' + CONDITION,
         "study.toml line 2: start_xy_m = [0.6, -0.4]: " + UNUSED),
        ('task = "pointing"\n[familiarization]\ntrials = 0\n' + CONDITION,
         "study.toml: familiarization: " + UNUSED),
        ('task = "pointing"\n[pointing]\ntimeout_s = 0\n' + CONDITION,
         "study.toml line 3: pointing.timeout_s = 0.0: expected a time above 0 and at most 600 s."),
        ('task = "pointing"\n[[conditions]]\ncues = []\nround_trip_ms = 40000\n',
         "study.toml: conditions: condition 1: round_trip_ms = 40000: expected less than "
         "pointing.timeout_s (40000 ms), or every trial times out."),
    ],
)  # fmt: skip
def test_a_pointing_design_out_of_range_is_refused_at_its_line(text: str, message: str) -> None:
    with pytest.raises(StudyDefinitionError) as err:
        parse_study(text, "study.toml")
    assert str(err.value) == message


def test_a_pointing_study_served_keeps_each_trial_on_its_plan(tmp_path: Path) -> None:
    """Served: the simulated run's plan, trial by trial; each ended trial's row lands in
    pointing.csv in plan order (its trace beside it), an interrupted one runs again, a restart
    carries on, and the folder is read as a pointing table."""
    study = parse_study(TINY)
    out = tmp_path / "run"
    with served_run(out, study) as run:
        assert isinstance(run, ServedPointingRun)
        blocks = pointing_blocks(study)
        assert [(s.block, s.round_trip_ms, s.trial) for s in run.plan] == [
            (b.block, b.round_trip_ms, t) for b in blocks for t in b.trials
        ]
        assert "4 measured trials, in 2 blocks" in consent_text(run.study)
        first, second = run.pending("F02")[:2]
        run.keep_interrupted(first)
        ws = run.trial_config(second, run.site).site.workspace
        t = np.arange(0.0, 3.0, 0.01)  # still over the cross, then at 0.2 m/s to the target
        y = ws.start_xy_m[1] + np.clip(0.2 * (t - 1.0), 0.0, 0.1)
        trace = {"time_s": t, "gripper_x_m": np.full_like(t, ws.start_xy_m[0]),
                 "gripper_y_m": y, "grip": (t >= 2.0).astype(float),
                 "gripper_closure": (t >= 2.1).astype(float)}  # fmt: skip
        said = run.keep_result(second, SimpleNamespace(trace=trace, outcome=Outcome.SUCCESS), 3.0)
        assert said == "Chosen in 1.00 s, 0 mm from the middle: inside the circle."
        assert [s.key for s in run.pending("F02")][:2] == [first.key, ("F02", 3)]
    with served_run(out) as again:  # a restarted server: the same session
        assert isinstance(again, ServedPointingRun) and again.instructed("F02")
        assert [s.key for s in again.pending("F02")] == [("F02", 1), ("F02", 3), ("F02", 4)]
    (row,) = list(csv.DictReader((out / "pointing.csv").open()))
    assert (row["participant"], row["trial"], row["block"], row["hit"], row["outcome"]) == (
        "F02", "2", "1", "1.0", "selected"
    )  # fmt: skip
    assert float(row["movement_time_s"]) == pytest.approx(1.0, abs=0.011)
    assert (out / row["trajectory_file"]).is_file()
    (cut,) = list(csv.DictReader((out / "interrupted.csv").open()))
    assert (cut["trial"], cut["outcome"]) == ("1", "interrupted")
    assert pointing_table_path(out) == out / "pointing.csv"
    with served_run(out) as last:  # the rest, each timed out; then the run is finished
        assert not last.finish_if_done()
        timed_out = SimpleNamespace(trace={**trace, "grip": np.zeros_like(t)},
                                    outcome=Outcome.TIMEOUT)  # fmt: skip
        for spec in last.pending("F02"):
            said = last.keep_result(spec, timed_out, 3.0)
        assert said == "No target counted: the time ran out before the grip closed."
        assert last.current() is None and last.finish_if_done()
    assert json.loads((out / "manifest.json").read_text())["finished"]
    rows = list(csv.DictReader((out / "pointing.csv").open()))
    assert [(r["trial"], r["outcome"]) for r in rows] == [
        ("1", "timeout"), ("2", "selected"), ("3", "timeout"), ("4", "timeout")
    ]  # fmt: skip

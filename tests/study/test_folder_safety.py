"""A run folder that two processes, an editor, a killed parent and a full disk cannot corrupt, and
the messages that replace tracebacks (issue 43's defects, one test or more each)."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from arteleop.analysis import analyse, load_study
from arteleop.cli import main
from arteleop.errors import RunFolderError
from arteleop.study import (
    CohortConfig,
    FamiliarizationConfig,
    RunFolder,
    StudyConfig,
    resume_study,
    run_lock,
    run_study,
)
from tests.analysis.make_study import make_run
from tests.analysis.test_delay import write_crossed

ARTELEOP = [sys.executable, "-m", "arteleop.cli"]
TINY = StudyConfig(
    seed=3,
    modalities=("none",),
    timeout_s=1.0,
    familiarization=FamiliarizationConfig(trials=0),
    cohort=CohortConfig(size=2, avr_experts=0, games_experts=0, both_experts=0),
)
"""Two participants, one trial each, one simulated second: a run in a few seconds."""


@pytest.fixture(scope="module")
def tiny_run(tmp_path_factory: pytest.TempPathFactory) -> Path:
    folder = tmp_path_factory.mktemp("tiny") / "run"
    run_study(TINY, folder, workers=1)
    return folder


def _copy(run: Path, to: Path) -> Path:
    subprocess.run(["cp", "-r", str(run), str(to)], check=True)
    return to


# 1. One writer per run folder -------------------------------------------------------------


def test_a_second_writer_is_refused_with_the_holders_pid(tiny_run: Path, tmp_path: Path) -> None:
    run = _copy(tiny_run, tmp_path / "run")
    holder = subprocess.Popen(
        [sys.executable, "-c", "import sys, time; from arteleop.study import run_lock; "
         "lock = run_lock(sys.argv[1]); lock.__enter__(); print('held', flush=True); "
         "time.sleep(60)", str(run)],
        stdout=subprocess.PIPE, text=True,
    )  # fmt: skip
    try:
        assert holder.stdout is not None and holder.stdout.readline() == "held\n"
        with pytest.raises(RunFolderError) as err:
            resume_study(run)
        assert str(err.value) == (
            f"{run} is being written by another arteleop (pid {holder.pid}): wait for it to "
            f"end, or stop it; then 'arteleop study resume {run}' continues the run."
        )
    finally:
        holder.kill()
        holder.wait()
    # The kernel dropped the lock with its holder, killed as it was: no stale lock.
    with run_lock(run):
        pass


def test_the_lock_is_reentrant_within_a_process(tmp_path: Path) -> None:
    with run_lock(tmp_path), run_lock(tmp_path):
        pass
    with run_lock(tmp_path):
        pass


# 2. Resume trusts only the definition the run began with ----------------------------------


@pytest.mark.parametrize(
    ("edit", "message"),
    [
        (("seed = 3", "seed = 4"), "its key 'seed' is 4, the run's 3"),
        (("size = 2", "size = 3"), "its key 'cohort.size' is 3, the run's 2"),
    ],
)
def test_resume_refuses_an_edited_definition_and_says_what_changed(
    tiny_run: Path, tmp_path: Path, edit: tuple[str, str], message: str
) -> None:
    run = _copy(tiny_run, tmp_path / "run")
    study = run / "study.toml"
    before = study.read_text()
    assert edit[0] in before
    study.write_text(before.replace(edit[0], edit[1], 1))
    trials = (run / "trials.csv").read_bytes()
    with pytest.raises(RunFolderError) as err:
        resume_study(run)
    assert str(err.value) == (
        f"{study} was edited after the run began: {message}. Put it back (manifest.json keeps "
        "the run's definition as 'definition'), or start a new run in another folder."
    )
    assert (run / "trials.csv").read_bytes() == trials


def test_a_comment_edited_in_the_definition_changes_nothing(tiny_run: Path, tmp_path: Path) -> None:
    run = _copy(tiny_run, tmp_path / "run")
    study = run / "study.toml"
    study.write_text("# my note\n" + study.read_text())
    with pytest.raises(RunFolderError, match="is complete: all 2 trials are in"):
        resume_study(run)


# 3. Resume never drops, merges or rewrites a row silently ---------------------------------


def test_a_whole_last_row_without_its_line_end_is_kept(tiny_run: Path, tmp_path: Path) -> None:
    run = _copy(tiny_run, tmp_path / "run")
    trials = run / "trials.csv"
    whole = trials.read_bytes()
    trials.write_bytes(whole[:-1])  # an editor saved it without the final line end
    with pytest.raises(RunFolderError) as err:
        resume_study(run)  # nothing to run: the last trial is still in
    assert "is complete: all 2 trials are in" in str(err.value)
    assert "a whole row without its line end; the line end is back." in str(err.value)
    assert trials.read_bytes() == whole


def test_duplicate_and_unplanned_rows_are_set_aside_and_said(
    tiny_run: Path, tmp_path: Path
) -> None:
    run = _copy(tiny_run, tmp_path / "run")
    trials = run / "trials.csv"
    lines = trials.read_text().splitlines(keepends=True)
    stranger = lines[1].replace("P01,", "P09,", 1)
    trials.write_text("".join([*lines, lines[1], stranger]))
    manifest = json.loads((run / "manifest.json").read_text())
    manifest["finished"] = None  # as if a kill came before the end
    (run / "manifest.json").write_text(json.dumps(manifest))
    done = resume_study(run)
    aside = run / "trials-set-aside.csv"
    assert aside.read_text() == lines[1] + stranger
    assert trials.read_text() == "".join(lines)
    assert done.notes == (
        f"{trials}: 1 second row(s) of a trial already in it; moved to {aside}.",
        f"{trials}: 1 row(s) of trials the plan does not have; moved to {aside}.",
    )


def test_a_row_whose_trajectory_was_deleted_runs_again(tiny_run: Path, tmp_path: Path) -> None:
    # The row alone was counted: resume said the run was complete.
    run = _copy(tiny_run, tmp_path / "run")
    trials, lost = run / "trials.csv", run / "trajectories" / "P02" / "1.csv"
    rows, trajectory = trials.read_text(), lost.read_bytes()
    lost.unlink()
    done = resume_study(run, workers=1)
    assert done.ran == 1 and lost.read_bytes() == trajectory  # same seed, same trial
    assert trials.read_text() == rows
    aside = run / "trials-set-aside.csv"
    assert aside.read_text() == rows.splitlines(keepends=True)[2]
    assert done.notes == (
        f"{trials}: 1 row(s) whose trajectory file is missing, whose trials run again; moved "
        f"to {aside}.",
    )


# 4. A recording is not replaced unless asked, and is written whole ------------------------


def test_operator_synth_refuses_to_replace_a_recording(tmp_path: Path, capsys) -> None:
    out = tmp_path / "rec.csv"
    out.write_text("mine\n")
    assert main(["operator", "synth", "--out", str(out), "--quiet"]) == 2
    assert capsys.readouterr().err == (
        f"arteleop: error: --out {out}: {out} exists; give another path, or --force to replace "
        "the recording.\n"
    )
    assert out.read_text() == "mine\n"


def test_a_recording_on_a_full_disk_leaves_the_old_one(tmp_path: Path, monkeypatch) -> None:
    from arteleop import files
    from arteleop.operator import Recording, RecordingInfo, load_recording, write_recording

    n = 300
    quats = np.tile([1.0, 0.0, 0.0, 0.0], (n, 3, 1))
    rec = Recording(np.arange(n) / 100, quats, np.zeros(n), RecordingInfo())
    out = tmp_path / "rec.csv"
    write_recording(rec, out)
    before = out.read_bytes()
    real = os.fsync

    def full(fd: int) -> None:
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(files.os, "fsync", full)
    with pytest.raises(OSError):
        write_recording(Recording(np.arange(n) / 100 + 1, quats, np.ones(n), RecordingInfo()), out)
    monkeypatch.setattr(files.os, "fsync", real)
    assert out.read_bytes() == before and load_recording(out).grip[0] == 0.0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["rec.csv", "rec.json"]


# 5. Workers die with their parent, however it dies ----------------------------------------


def _children(pid: int) -> set[int]:
    out = subprocess.run(["ps", "-o", "pid=", "--ppid", str(pid)], capture_output=True,
                         text=True).stdout  # fmt: skip
    return {int(x) for x in out.split()}


@pytest.mark.parametrize("sig", [signal.SIGKILL, signal.SIGTERM])
def test_workers_end_when_their_parent_is_killed(tmp_path: Path, sig: signal.Signals) -> None:
    study = tmp_path / "s.toml"
    study.write_text("modalities = ['none', 'full']\ntimeout_s = 60.0\n[familiarization]\n"
                     "trials = 0\n[cohort]\nsize = 4\navr_experts = 0\ngames_experts = 0\n"
                     "both_experts = 0\n")  # fmt: skip
    parent = subprocess.Popen([*ARTELEOP, "study", "run", str(study), "--out",
                               str(tmp_path / "run"), "--workers", "2", "--quiet"])  # fmt: skip
    deadline = time.monotonic() + 60
    while len(workers := _children(parent.pid)) < 2 and time.monotonic() < deadline:
        time.sleep(0.2)
    assert len(workers) == 2
    parent.send_signal(sig)
    parent.wait()
    deadline = time.monotonic() + 10
    while any(Path(f"/proc/{w}").exists() for w in workers) and time.monotonic() < deadline:
        time.sleep(0.2)
    assert not any(Path(f"/proc/{w}").exists() for w in workers)


def test_the_workers_are_no_more_than_the_trials(tmp_path: Path, monkeypatch) -> None:
    import arteleop.study.worker_pool as worker_pool

    made = []
    real = worker_pool.ProcessPoolExecutor

    def pool(workers: int, **kwargs):
        made.append(workers)
        return real(workers, **kwargs)

    monkeypatch.setattr(worker_pool, "ProcessPoolExecutor", pool)
    run_study(TINY, tmp_path / "run", workers=64)
    assert made == [2]


# 6. A report is finished only once its last file is in ------------------------------------


def test_a_report_cut_by_a_full_disk_is_not_kept_and_resume_writes_it(
    tiny_run: Path, tmp_path: Path, monkeypatch, capsys
) -> None:
    run = _copy(tiny_run, tmp_path / "run")
    manifest = json.loads((run / "manifest.json").read_text())
    manifest["report_finished"] = None
    (run / "manifest.json").write_text(json.dumps(manifest))
    real = pd.DataFrame.to_csv

    def full(self, path, *args, **kwargs):
        if str(path).endswith("normality.csv"):
            raise OSError(28, "No space left on device")
        return real(self, path, *args, **kwargs)

    monkeypatch.setattr(pd.DataFrame, "to_csv", full)
    assert main(["study", "resume", str(run), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert err == (
        f"arteleop: error: Cannot write the report to {run / 'report'}: No space left on device. "
        "Nothing of it was kept; free space or fix permissions and analyse again. The trials "
        f"are all in {run}; 'arteleop study resume {run}' writes it.\n"
    )
    # Nothing of the report was kept, not even its hidden folder; the trials are untouched.
    assert sorted(p.name for p in run.iterdir() if "report" in p.name) == []
    assert not RunFolder(run).report_finished()
    monkeypatch.setattr(pd.DataFrame, "to_csv", real)
    assert main(["study", "resume", str(run), "--quiet"]) == 0
    assert "its report is not whole: writing it" in capsys.readouterr().out
    assert RunFolder(run).report_finished()


def test_a_killed_writers_hidden_folders_go_a_live_ones_stay(
    tiny_run: Path, tmp_path: Path
) -> None:
    """A writer killed while writing a report leaves its hidden folder; the next write removes
    it (seen in a run killed at a random moment), but not one of a writer still at work."""
    run = _copy(tiny_run, tmp_path / "run")
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    left = [run / f".report.partial-{dead.pid}", run / f".report.old-{dead.pid}"]
    working = run / f".report.partial-{os.getppid()}"
    for folder in (*left, working):
        folder.mkdir()
        (folder / "tests.csv").write_text("cut")
    assert main(["analyze", str(run), "--out", str(run / "report"), "--force"]) == 0
    assert [p.exists() for p in left] == [False, False]
    assert working.exists()


def test_analyze_does_not_replace_a_report_unless_asked(tiny_run: Path, tmp_path: Path,
                                                         capsys) -> None:  # fmt: skip
    out = tmp_path / "report"
    assert main(["analyze", str(tiny_run), "--out", str(out)]) == 0
    assert main(["analyze", str(tiny_run), "--out", str(out)]) == 2
    assert capsys.readouterr().err.endswith(
        f"--out {out} holds an earlier report; give a new folder, or --force to replace it.\n"
    )
    assert main(["analyze", str(tiny_run), "--out", str(out), "--force"]) == 0
    assert main(["analyze", str(tiny_run), "--out", str(tiny_run), "--force"]) == 2
    assert capsys.readouterr().err.endswith(
        f"--out {tiny_run}: it holds the data analysed ({tiny_run}); give a new folder, such "
        f"as {tiny_run / 'report'}.\n"
    )


# 7. Paths from data stay inside their folder ----------------------------------------------


@pytest.mark.parametrize("escape", ["/etc/hostname", "../../../../etc/hostname"])
def test_a_trajectory_path_outside_the_folder_is_refused_by_row(
    tmp_path: Path, escape: str
) -> None:
    run = make_run(tmp_path / "run", trajectories=False)
    trials = pd.read_csv(run / "trials.csv", dtype=str, keep_default_na=False)
    trials.loc[4, "trajectory_file"] = escape
    trials.to_csv(run / "trials.csv", index=False)
    with pytest.raises(Exception) as err:
        load_study(run)
    assert str(err.value) == (
        f"{run / 'trials.csv'}, line 6, column trajectory_file: '{escape}' is outside the "
        "folder of the trials file; a trajectory file's path is relative to it, inside it "
        "(trajectories/P01/1.csv)"
    )


# 8. inf is refused like nan ---------------------------------------------------------------


@pytest.mark.parametrize("column", ["completion_time_s", "placement_error_m"])
def test_inf_is_refused_like_nan(tmp_path: Path, column: str) -> None:
    run = make_run(tmp_path / "run", trajectories=False)
    trials = pd.read_csv(run / "trials.csv", dtype=str, keep_default_na=False)
    trials.loc[3, column] = "inf"
    trials.to_csv(run / "trials.csv", index=False)
    with pytest.raises(Exception) as err:
        load_study(run)
    assert str(err.value) == (
        f"{run / 'trials.csv'}, line 5, column {column}: 'inf' is not a finite number"
    )


# 10. An analysis of a design that does not cross every cue with every delay ----------------


def test_an_uncrossed_delay_design_is_analysed_on_its_crossed_part(tmp_path: Path) -> None:
    table = write_crossed(tmp_path / "trials.csv", interaction=True)
    # No AR at 0 and 500 ms, the predictive ghost at 500 ms only: a common design.
    table = table[~((table["modality"] == "predictive") & (table["round_trip_ms"] == 0))]
    table.to_csv(tmp_path / "trials.csv", index=False)
    result = analyse(load_study(tmp_path / "trials.csv"))
    anova = result.tests[result.tests["subset"] == "delay x cue"]
    assert set(anova["test"]) == {""}  # not run
    assert anova["note"].iloc[0].startswith("the design does not cross cue sets with delays")
    pairs = result.tests[result.tests["subset"] == "all @ 500ms"]
    assert {"none", "predictive"} <= set(pairs["group_a"]) | set(pairs["group_b"])

"""Bad input gets one line that names the file, line, option or value and what was expected;
never a traceback (issue 43, items 9, 11 and 12)."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pandas as pd
import pytest

from arteleop.cli import main
from tests.analysis.make_study import make_run
from tests.helpers import ctrl_c_reaches_it

ARTELEOP = [sys.executable, "-m", "arteleop.cli"]


def _error(argv: list[str], capsys) -> str:
    assert main(argv) == 2
    captured = capsys.readouterr()
    assert "Traceback" not in captured.err
    return captured.err.removeprefix("arteleop: error: ").rstrip("\n")


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("", "s.toml defines nothing (no key). 'arteleop study run' without a file runs the "
             "built-in default study; 'arteleop study init FILE' writes it to edit."),
        ("[cohort]\nsize = 100000000\n",
         "s.toml line 2: cohort.size = 100000000: expected at most 10000 participants. A run "
         "plans every trial before the first runs and keeps them in one folder: run a larger "
         "cohort as several runs with other seeds and pool them with 'arteleop analyze RUN1 "
         "RUN2 ...'."),
        ("[cohort]\nsize = 1e23\n",
         "s.toml line 2: cohort.size must be a whole number, got 1e+23."),
        ("[[conditions]]\ncues = []\n[[conditions]]\n",
         "s.toml line 3: an empty [[conditions]] table; give its cues (cues = [] for no AR) and, "
         "for a delay, round_trip_ms."),
        ("conditions = []\n",
         "s.toml line 1: conditions = [] gives no condition; give [[conditions]] tables (each a "
         "cue set over a network profile), or remove the key to compare the modalities."),
        ("\ufeff[cohort]\nsize = 0\n", "s.toml line 2: cohort.size = 0: expected 1 or more."),
    ],
)  # fmt: skip
def test_a_study_file_that_cannot_run_is_refused_before_anything_runs(
    tmp_path: Path, monkeypatch, capsys, text: str, message: str
) -> None:
    monkeypatch.chdir(tmp_path)
    Path("s.toml").write_text(text, encoding="utf-8")
    assert _error(["study", "run", "s.toml", "--out", "run"], capsys) == message
    assert not Path("run").exists()


def test_study_run_into_a_file_is_refused(tmp_path: Path, capsys) -> None:
    out = tmp_path / "notes.txt"
    out.write_text("mine\n")
    assert _error(["study", "run", "--out", str(out)], capsys) == (
        f"--out {out}: a file, not a folder; give a new folder."
    )
    assert out.read_text() == "mine\n"


def test_analyze_into_a_file_is_refused(tmp_path: Path, capsys) -> None:
    run = make_run(tmp_path / "run", trajectories=False)
    out = tmp_path / "notes.txt"
    out.write_text("mine\n")
    assert _error(["analyze", str(run), "--out", str(out)], capsys) == (
        f"--out {out}: a file, not a folder; give a new folder."
    )


@pytest.mark.parametrize(
    ("content", "message"),
    [
        (b"participant,phase,trial_index,modality,position,outcome,completion_time_s,"
         b"placement_error_m\n", "no trials below the header"),
        (b"participant,phase\n\xff\xfe\n", "not UTF-8 text; save it as UTF-8 CSV"),
    ],
)  # fmt: skip
def test_analyze_refuses_an_empty_or_undecodable_table(
    tmp_path: Path, capsys, content: bytes, message: str
) -> None:
    trials = tmp_path / "trials.csv"
    trials.write_bytes(content)
    assert _error(["analyze", str(trials), "--out", str(tmp_path / "r")], capsys) == (
        f"{trials}: {message}"
    )


@pytest.mark.parametrize(
    ("table", "row", "column", "value", "message"),
    [
        ("trials.csv", 2, "outcome", "wizard",
         "unknown value 'wizard'. Expected one of: success, timeout, tracking_lost, dropped, "
         "not_grasped, operator_stopped, interrupted, failure"),
        ("participants.csv", 0, "age", "-5", "-5; expected 0 to 120"),
    ],
)  # fmt: skip
def test_analyze_refuses_a_value_out_of_its_set(
    tmp_path: Path, capsys, table: str, row: int, column: str, value: str, message: str
) -> None:
    run = make_run(tmp_path / "run", trajectories=False)
    df = pd.read_csv(run / table, dtype=str, keep_default_na=False)
    df.loc[row, column] = value
    df.to_csv(run / table, index=False)
    assert _error(["analyze", str(run), "--out", str(tmp_path / "r")], capsys) == (
        f"{run / table}, line {row + 2}, column {column}: {message}"
    )


def _run_folder(tmp_path: Path) -> Path:
    """A run folder as study run begins it: study.toml and the manifest, no trial yet."""
    from arteleop.study import parse_study
    from arteleop.study.run_opening import new_manifest, plan_run

    run = tmp_path / "run"
    run.mkdir()
    (run / "study.toml").write_text("seed = 0\n")
    plan, people = plan_run(parse_study("seed = 0\n", "study.toml"))
    manifest = new_manifest(parse_study("seed = 0\n", "study.toml"), "seed = 0\n", plan,
                            len(people))  # fmt: skip
    (run / "manifest.json").write_text(json.dumps(manifest))
    return run


@pytest.mark.parametrize("key", ["definition", "definition_sha256", "plan_sha256"])
def test_resume_with_a_manifest_that_cannot_vouch_for_the_run(
    tmp_path: Path, capsys, key: str
) -> None:
    # A null definition digest resumed without checking the definition.
    run = _run_folder(tmp_path)
    manifest = json.loads((run / "manifest.json").read_text())
    (run / "manifest.json").write_text(json.dumps(manifest | {key: None}))
    assert _error(["study", "resume", str(run)], capsys) == (
        f"{run / 'manifest.json'}: its 'definition', 'definition_sha256' or 'plan_sha256' is "
        "missing, null or edited, so the run cannot be checked against what it began with. "
        "Restore manifest.json from a backup."
    )


def test_resume_with_a_manifest_that_is_not_an_object(tmp_path: Path, capsys) -> None:
    run = _run_folder(tmp_path)
    (run / "manifest.json").write_text("[1, 2]\n")
    assert _error(["study", "resume", str(run)], capsys) == (
        f"{run / 'manifest.json'}: a JSON list, expected an object with the run's "
        "format_version, seed and packages; restore it from a backup."
    )


def test_resume_with_a_trial_index_that_is_not_a_number(tmp_path: Path, capsys) -> None:
    from arteleop.study import TRIAL_COLUMNS

    run = _run_folder(tmp_path)
    row = dict.fromkeys(TRIAL_COLUMNS, "")
    row.update(participant="P01", trial_index="two")
    (run / "trials.csv").write_text(",".join(TRIAL_COLUMNS) + "\n" + ",".join(row.values()) + "\n")
    assert _error(["study", "resume", str(run)], capsys) == (
        f"{run / 'trials.csv'} line 2, column trial_index: 'two'; expected a whole number. "
        "Correct the row or move it out of the file, then resume."
    )


def _recording(tmp_path: Path) -> Path:
    out = tmp_path / "rec.csv"
    assert main(["operator", "synth", "--out", str(out), "--quiet", "--seed", "1"]) == 0
    return out


@pytest.fixture(scope="module")
def recording(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return _recording(tmp_path_factory.mktemp("rec"))


@pytest.mark.parametrize(
    ("edit", "message"),
    [
        (lambda side: [side], "a JSON list; expected an object with format, version, rate_hz, "
         "arm, calibration_posture, subject_id and units (docs/reference/recording-format.md)"),
        (lambda side: side | {"rate_hz": 0}, "RecordingInfo.rate_hz = 0.0: expected 10.0-1000.0 "
         "(Hz, an IMU's sample rate)."),
        (lambda side: side | {"rate_hz": 1e6}, "RecordingInfo.rate_hz = 1000000.0: expected "
         "10.0-1000.0 (Hz, an IMU's sample rate)."),
    ],
)  # fmt: skip
def test_a_sidecar_that_cannot_be_is_refused_by_check_and_trial(
    recording: Path, tmp_path: Path, capsys, edit, message: str
) -> None:
    csv = tmp_path / "r.csv"
    csv.write_bytes(recording.read_bytes())
    side = json.loads(recording.with_suffix(".json").read_text())
    csv.with_suffix(".json").write_text(json.dumps(edit(side)))
    for command in (["operator", "check", str(csv)], ["trial", "--operator", str(csv)]):
        assert _error(command, capsys) == f"{csv.with_suffix('.json')}: {message}"


def test_operator_synth_into_a_folder_is_refused(tmp_path: Path, capsys) -> None:
    assert _error(["operator", "synth", "--out", str(tmp_path)], capsys) == (
        f"--out {tmp_path}: a folder; give the recording's CSV path, such as "
        f"{tmp_path / 'synthetic.csv'}."
    )


def test_ctrl_c_stops_teleop_and_its_render_process_without_a_traceback() -> None:
    """Ctrl-C reaches the whole process group: the render process stays quiet."""
    view = subprocess.Popen([*ARTELEOP, "teleop", "--port", "0"], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, start_new_session=True,
                            preexec_fn=ctrl_c_reaches_it)  # fmt: skip
    assert view.stdout is not None and "operator's view at" in view.stdout.readline()
    time.sleep(3)  # trials under way: the render process is drawing
    os.killpg(view.pid, signal.SIGINT)
    _, err = view.communicate(timeout=60)
    assert view.returncode == 130
    assert err == "arteleop: interrupted\n"


@pytest.mark.parametrize("name", ["trials.csv", "participants.csv"])
def test_a_run_folders_table_that_is_a_link_is_not_followed(
    tmp_path: Path, capsys, name: str
) -> None:
    # Followed, the error quoted the target's first line (/etc/shadow's, run as root).
    secret = tmp_path / "secret"
    secret.write_text("root:$6$hash:19000:0:99999:7:::\n")
    run = _run_folder(tmp_path)
    (run / "trials.csv").write_text("participant,phase\n")
    (run / name).unlink(missing_ok=True)
    (run / name).symlink_to(secret)
    assert _error(["analyze", str(run), "--out", str(tmp_path / "r")], capsys) == (
        f"{run / name}: a symbolic link; a run folder's tables are read only as files in it (a "
        "link could put another file's lines into a message): copy the file itself into the "
        "folder"
    )
    assert _error(["study", "resume", str(run)], capsys) == (
        f"{run / name}: a symbolic link in a run folder, which reads and writes only its own "
        "files; put the file itself there, or start a new run in another folder."
    )

"""Running a study: the same bytes in series, in parallel, on a Dask cluster and after kill -9."""

from __future__ import annotations

import contextlib
import json
import os
import shutil
import signal
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest

from arteleop.blas_kernel import blas_description
from arteleop.cli import main
from arteleop.errors import RunFolderError
from arteleop.numpy_loops import numpy_loops_description, running_avx512_targets
from arteleop.operator import OperatorParams, SeenOutcomes
from arteleop.study import (
    CohortConfig,
    FamiliarizationConfig,
    RunComplete,
    RunFolder,
    StudyConfig,
    resume_study,
    run_study,
    study_text,
)
from arteleop.study.carry import Carried
from arteleop.study.protocol import run_planned_trial
from arteleop.study.run_opening import arithmetic_notes, new_manifest, record_resume

# Two participants, two modalities, one practice trial: six trials of a few simulated seconds,
# long enough for the second and third to teach the operator something of the display's lag.
SMALL = StudyConfig(
    seed=5,
    modalities=("none", "full"),
    timeout_s=8.0,
    familiarization=FamiliarizationConfig(trials=1, timeout_s=2.0),
    cohort=CohortConfig(size=2, avr_experts=1, games_experts=1, both_experts=0),
)


def _files(folder: Path) -> dict[str, bytes]:
    """Every file of a run but the manifest (its start and end times differ), the lock (the
    process id of its last writer) and the report."""
    return {
        str(p.relative_to(folder)): p.read_bytes()
        for p in sorted(folder.rglob("*"))
        if p.is_file()
        and p.name not in ("manifest.json", ".arteleop.lock")
        and "report" not in p.parts
    }


@pytest.fixture(scope="module")
def chained(tmp_path_factory: pytest.TempPathFactory) -> tuple[dict[str, bytes], list, Path]:
    """The small study in series: its files, each trial's (participant, trial_index) with what
    its participant brought to it (the lag believed, the misses seen), and the run folder."""
    folder = tmp_path_factory.mktemp("series") / "run"
    given: list = []
    with _brought_to(given):
        run = run_study(SMALL, folder, workers=1)
    assert run.ran == 6 and len(run.trials) == 6
    return _files(folder), given, folder


@contextlib.contextmanager
def _brought_to(given: list) -> Iterator[None]:
    """Within: each trial the runner runs adds its (participant, trial_index) and what its
    participant brought to it to ``given``."""

    def spy(study, site, person, spec, brought=None):
        given.append((spec.key, brought))
        return run_planned_trial(study, site, person, spec, brought)

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr("arteleop.study.runner.run_planned_trial", spy)
        yield


@pytest.fixture(scope="module")
def series(chained: tuple[dict[str, bytes], list, Path]) -> dict[str, bytes]:
    return chained[0]


def test_each_trial_brings_the_lag_and_the_misses_seen_in_the_ones_before(
    chained: tuple[dict[str, bytes], list, Path],
) -> None:
    files, given, _ = chained
    lines = files["trials.csv"].decode().splitlines()
    header = lines[0].split(",")
    rows = [dict(zip(header, line.split(","), strict=True)) for line in lines[1:]]
    ends = {(r["participant"], int(r["trial_index"])): float(r["believed_lag_s"]) for r in rows}
    # Every trial of 8 s or less times out: a failure is a miss the participant knows.
    assert [(r["outcome"], r["saw_miss"]) for r in rows] == [("timeout", "1")] * 6

    def carried(person: str, last: int) -> Carried:
        return Carried(ends[person, last], SeenOutcomes(trials=last, misses=last))

    assert given == [
        (("P01", 1), None), (("P01", 2), carried("P01", 1)), (("P01", 3), carried("P01", 2)),
        (("P02", 1), None), (("P02", 2), carried("P02", 1)), (("P02", 3), carried("P02", 2)),
    ]  # fmt: skip
    familiar = OperatorParams().familiar_lag_s
    # The practice trial is too short to teach it anything; the next ones teach it a little.
    assert ends["P01", 1] == ends["P02", 1] == familiar
    assert ends["P01", 2] != familiar and ends["P01", 3] != ends["P01", 2]


def test_a_run_holds_every_file_of_the_format(series: dict[str, bytes]) -> None:
    assert sorted(series) == [
        "participants.csv", "questionnaire.csv", "study.toml",
        *(f"trajectories/{p}/{i}.csv" for p in ("P01", "P02") for i in (1, 2, 3)),
        "trials.csv",
    ]  # fmt: skip
    lines = series["trials.csv"].decode().splitlines()
    assert [line.split(",")[:5] for line in lines[1:]] == [
        ["P01", "familiarization", "1", "none", "1"],
        ["P01", "experimental", "2", "none", "1"],
        ["P01", "experimental", "3", "full", "2"],
        ["P02", "familiarization", "1", "none", "1"],
        ["P02", "experimental", "2", "full", "1"],
        ["P02", "experimental", "3", "none", "2"],
    ]
    trace = series["trajectories/P01/2.csv"].decode().splitlines()
    assert len(trace) == 1 + 801  # 8 s at 100 Hz, both ends
    assert trace[0].startswith("time_s,hand_x_m,hand_y_m,hand_z_m,grip,upper_arm_qw,")
    assert series["study.toml"].decode() == study_text(SMALL)
    assert len(series["questionnaire.csv"].decode().splitlines()) == 1 + 2 * 9


def test_parallel_workers_write_the_same_bytes(series: dict[str, bytes], tmp_path: Path) -> None:
    run_study(SMALL, tmp_path / "run", workers=2)
    assert _files(tmp_path / "run") == series


def test_a_dask_cluster_writes_the_same_bytes(series: dict[str, bytes], tmp_path: Path) -> None:
    distributed = pytest.importorskip("distributed")
    with (
        distributed.LocalCluster(
            n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
        ) as cluster,
        distributed.Client(cluster) as client,
    ):
        run_study(SMALL, tmp_path / "run", executor=client.get_executor())
    assert _files(tmp_path / "run") == series


def _start_small_run(tmp_path: Path, workers: int) -> tuple[Path, list[str], subprocess.Popen]:
    """``arteleop study run`` of the small study into ``tmp_path/run``, started in a child."""
    definition = tmp_path / "small.toml"
    definition.write_text(study_text(SMALL))
    folder = tmp_path / "run"
    command = [sys.executable, "-m", "arteleop.cli", "study", "run", str(definition),
               "--out", str(folder), "--workers", str(workers), "--quiet"]  # fmt: skip
    child = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return folder, command, child


def test_a_run_killed_midway_resumes_to_the_same_bytes(
    series: dict[str, bytes], tmp_path: Path
) -> None:
    folder, _, child = _start_small_run(tmp_path, workers=1)
    trials = folder / "trials.csv"
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and child.poll() is None:
        if trials.exists() and trials.read_text().count("\n") >= 3:  # header and two trials
            break
        time.sleep(0.05)
    os.kill(child.pid, signal.SIGKILL)
    child.wait()
    kept = trials.read_text().count("\n") - 1
    assert 2 <= kept < 6
    run = resume_study(folder, workers=1)
    assert run.ran == 6 - kept
    assert _files(folder) == series
    with pytest.raises(RunComplete, match=r"is complete: all 6 trials are in; nothing to resume"):
        resume_study(folder)


def test_a_run_killed_at_a_random_moment_resumes_to_the_same_bytes(
    series: dict[str, bytes], tmp_path: Path
) -> None:
    """The parent killed at a seeded random moment (starting, among the trials with two
    workers, or writing the report): the workers end with it, and resume finishes the run with
    the same bytes and a whole report. One moment (a second one cost the suite 11 s; Ctrl-C's
    test stops a parallel run at another; test_folder_safety repairs rows a kill cut short)."""
    delay_s = float(np.random.default_rng([43, 0]).uniform(2.0, 14.0))
    folder, command, child = _start_small_run(tmp_path, workers=2)
    try:
        child.wait(timeout=delay_s)
    except subprocess.TimeoutExpired:
        os.kill(child.pid, signal.SIGKILL)
        child.wait()
    if RunFolder(folder).is_run_folder():
        again = [*command[:4], "resume", str(folder), "--workers", "2", "--quiet"]
    else:  # killed before the run had begun: it begins again, in the same folder
        again = command
    done = subprocess.run(again, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, (delay_s, done.stderr)
    assert _files(folder) == series, delay_s
    assert RunFolder(folder).report_finished()
    assert (folder / "report" / "report.md").is_file()


def test_resume_carries_on_through_a_trial_run_again(
    chained: tuple[dict[str, bytes], list, Path], tmp_path: Path
) -> None:
    """P01's first trial lost its trajectory (set aside, run again) and its third is not run
    yet: the third brings what the second carried, the misses of the first among them."""
    files, given, original = chained
    folder = tmp_path / "run"
    shutil.copytree(original, folder)
    (folder / "trajectories" / "P01" / "1.csv").unlink()
    (folder / "trajectories" / "P01" / "3.csv").unlink()
    trials = folder / "trials.csv"
    header, *rows = trials.read_text().splitlines()
    trials.write_text("\n".join([header, rows[0], rows[1], *rows[3:]]) + "\n")
    again: list = []
    with _brought_to(again):
        run = resume_study(folder, workers=1)
    assert again == [given[0], given[2]]
    assert {k: v for k, v in _files(folder).items() if k != "trials-set-aside.csv"} == files
    assert not [n for n in run.notes if "computes otherwise" in n], "the same machine"


def test_resume_on_a_machine_that_computes_otherwise_says_so(
    chained: tuple[dict[str, bytes], list, Path], tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    _, _, original = chained
    folder = tmp_path / "run"
    shutil.copytree(original, folder)
    trials = folder / "trials.csv"
    lines = trials.read_text().splitlines(keepends=True)
    trials.write_text("".join(lines[:-1]))
    manifest = json.loads((folder / "manifest.json").read_text())
    assert "resumed" not in manifest  # a run that never stopped
    here_on = bool(running_avx512_targets())
    manifest["numpy_loops"] = "X86_V3" if here_on else "X86_V3 X86_V4 AVX512_ICL AVX512_SPR"
    (folder / "manifest.json").write_text(json.dumps(manifest))
    assert main(["study", "resume", str(folder), "--workers", "1", "--quiet"]) == 0
    there, here = ("off", "on") if here_on else ("on", "off")
    note = (
        f"note: {folder / 'manifest.json'}: the run began on a machine that computes otherwise "
        f"(numpy's AVX-512 loops {there} there, {here} here): the trials run now are this "
        "machine's, and differ from those that one would have written as another seed's do "
        "(docs/results/reproducibility.md). For a run computed alike throughout, resume it where "
        "it began, or set OPENBLAS_CORETYPE and NPY_DISABLE_CPU_FEATURES as there."
    )
    out = capsys.readouterr().out.splitlines()
    # Said once, before the trials run (their summary follows).
    assert out.count(note) == 1 and out.index(note) < next(
        k for k, line in enumerate(out) if line.endswith("(1 run now)")
    )
    # The manifest keeps what the run began on, and adds where it was resumed and from where.
    after = json.loads((folder / "manifest.json").read_text())
    assert after["numpy_loops"] == manifest["numpy_loops"]
    (resumed,) = after["resumed"]
    assert resumed["trials_in"] == len(lines) - 2  # the header and the trial run again
    assert (resumed["blas"], resumed["numpy_loops"]) == (
        blas_description(),
        numpy_loops_description(),
    )
    assert resumed["packages"] == manifest["packages"] and resumed["started"] >= manifest["started"]


def test_a_blas_or_package_version_is_told_apart_from_the_machines_arithmetic(
    tmp_path: Path,
) -> None:
    folder = RunFolder(tmp_path)
    *_, kernel = blas_description().split()
    same = {"blas": blas_description(), "numpy_loops": numpy_loops_description(),
            "packages": dict(new_manifest(SMALL, "", [], 0)["packages"])}  # fmt: skip
    assert arithmetic_notes(folder, same) == []
    # Another OpenBLAS build of the same kernel computes alike: nothing to set.
    assert arithmetic_notes(folder, same | {"blas": f"openblas 0.3.1 {kernel}"}) == []
    other = "Sandybridge" if kernel != "Sandybridge" else "Haswell"
    (note,) = arithmetic_notes(folder, same | {"blas": f"openblas 0.3.1 {other}"})
    assert f"(BLAS kernel {other} there, {kernel} here)" in note
    older = same["packages"] | {"pybullet": "0.0.1"}
    (note,) = arithmetic_notes(folder, same | {"packages": older})
    here_version = same["packages"]["pybullet"]
    assert note == (
        f"{tmp_path / 'manifest.json'}: the run began with other versions (pybullet 0.0.1 "
        f"there, {here_version} here): the trials run now may differ from those it would have "
        "written. For a run computed alike throughout, install the versions its 'packages' lists."
    )


def test_each_resume_is_recorded_and_the_last_one_compared_with(tmp_path: Path) -> None:
    """Begun and resumed here, then resumed elsewhere: the next resume here says so, though the
    run began on this machine's arithmetic."""
    folder = RunFolder(tmp_path)
    here = dict(new_manifest(SMALL, "", [], 0))
    folder.write_manifest(here)
    record_resume(folder, 2)
    record_resume(folder, 5)
    manifest = folder.manifest()
    assert [r["trials_in"] for r in manifest["resumed"]] == [2, 5]
    assert arithmetic_notes(folder, manifest) == []
    on = bool(running_avx512_targets())
    manifest["resumed"][-1] |= {"numpy_loops": "X86_V3" if on else "X86_V3 X86_V4",
                                "packages": here["packages"] | {"numpy": "0.0.1"}}  # fmt: skip
    loops, versions = arithmetic_notes(folder, manifest)
    assert loops.startswith(
        f"{tmp_path / 'manifest.json'}: the run was last resumed on a machine that computes "
        f"otherwise (numpy's AVX-512 loops {'off' if on else 'on'} there, {'on' if on else 'off'} "
        "here)"
    )
    assert versions.startswith(
        f"{tmp_path / 'manifest.json'}: the run was last resumed with other versions (numpy "
        f"0.0.1 there, {here['packages']['numpy']} here)"
    )
    folder.write_manifest(here | {"resumed": "twice"})
    with pytest.raises(RunFolderError, match=r"'resumed' is 'twice', expected a list"):
        record_resume(folder, 7)


def test_resume_removes_what_a_write_cut_short_left(
    chained: tuple[dict[str, bytes], list, Path], tmp_path: Path
) -> None:
    """Killed while writing P02's third trajectory: its temporary file stays beside it, the
    trial's row never written. Resume runs the trial and leaves the folder as a whole run's."""
    files, _, original = chained
    folder = tmp_path / "run"
    shutil.copytree(original, folder)
    (folder / "trajectories" / "P02" / "3.csv").rename(
        folder / "trajectories" / "P02" / ".3.csv.dhp1_l2s.tmp"
    )
    trials = folder / "trials.csv"
    trials.write_text("".join(trials.read_text().splitlines(keepends=True)[:-1]))
    kept = folder / "trajectories" / ".notes.tmp"  # not one of arteleop's: kept
    kept.write_text("mine")
    assert resume_study(folder, workers=1).ran == 1
    assert {k: v for k, v in _files(folder).items() if k != "trajectories/.notes.tmp"} == files
    assert kept.read_text() == "mine"


@pytest.mark.parametrize(
    ("column", "value", "expected"),
    [("believed_lag_s", "soon", "seconds (0 or more) or empty"), ("saw_miss", "2", "0 or 1")],
)
def test_resume_refuses_what_a_participant_carried_that_cannot_be_read(
    chained: tuple[dict[str, bytes], list, Path],
    tmp_path: Path,
    column: str,
    value: str,
    expected: str,
) -> None:
    folder = tmp_path / "run"
    shutil.copytree(chained[2], folder)
    trials = folder / "trials.csv"
    header, *rows = trials.read_text().splitlines()
    fields = rows[1].split(",")
    fields[header.split(",").index(column)] = value
    trials.write_text("\n".join([header, rows[0], ",".join(fields), *rows[2:5]]) + "\n")
    with pytest.raises(RunFolderError) as err:
        resume_study(folder, workers=1)
    assert str(err.value) == (
        f"{trials}, participant P01 trial 2, column {column}: {value!r}; expected {expected}. "
        "Correct the row or move it out of the file, then resume."
    )
    assert trials.read_text().count("\n") == 1 + 5  # nothing run, nothing set aside


def test_resume_refuses_what_is_not_its_run(tmp_path: Path, capsys) -> None:
    empty = tmp_path / "empty"
    empty.mkdir()
    with pytest.raises(RunFolderError) as err:
        resume_study(empty)
    assert str(err.value) == (
        f"{empty} is not a run folder (it has no study.toml and manifest.json): 'arteleop study "
        "run --out DIR' starts one."
    )
    assert list(empty.iterdir()) == []
    folder = tmp_path / "run"
    folder.mkdir()
    (folder / "study.toml").write_text(study_text(SMALL))
    (folder / "manifest.json").write_text('{"format_version": 1}')
    (folder / "trials.csv").write_text("participant\n")
    other = StudyConfig(seed=6, modalities=SMALL.modalities, timeout_s=SMALL.timeout_s,
                        familiarization=SMALL.familiarization, cohort=SMALL.cohort)  # fmt: skip
    with pytest.raises(RunFolderError) as err:
        resume_study(folder, other)
    assert str(err.value) == (
        f"{folder} was made from another definition: its key 'seed' is 5, the given one 6. "
        "Resume it without a definition, or start a new run in another folder."
    )
    with pytest.raises(RunFolderError, match=r"already holds a run: 'arteleop study resume"):
        run_study(SMALL, folder)
    # A study served to people is continued by study serve: resume refuses it.
    (folder / "manifest.json").write_text('{"format_version": 1, "cohort": "real"}')
    with pytest.raises(RunFolderError) as err:
        run_study(SMALL, folder)
    assert str(err.value) == (
        f"{folder} already holds a run: 'arteleop study serve --out {folder}' continues it; "
        "give --out a new folder for a new run."
    )
    assert main(["study", "resume", str(empty)]) == 2
    assert "is not a run folder" in capsys.readouterr().err


def test_out_of_reach_points_are_refused_before_anything_runs(tmp_path: Path, capsys) -> None:
    far = tmp_path / "far.toml"
    far.write_text("target_xy_m = [0.95, -0.1]\n")
    assert main(["study", "run", str(far), "--out", str(tmp_path / "run")]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"arteleop: error: {far} line 1: target_xy_m: The target point (0.95, "
                          "-0.1) m is out of the right arm's reach from above")  # fmt: skip
    assert not (tmp_path / "run").exists()
    assert main(["study", "run", "unknown.toml"]) == 2
    assert capsys.readouterr().err == (
        "arteleop: error: unknown.toml: no such study file. 'arteleop study init unknown.toml' "
        "writes the default one to edit.\n"
    )


def test_a_replay_shows_the_recorded_states_with_the_modalitys_layers(tmp_path: Path) -> None:
    from arteleop.robot import RIGHT_ARM_JOINTS
    from arteleop.scene import HeadCameraConfig, RemoteSite
    from arteleop.study.replay import load_replay, replay, replay_site

    one = StudyConfig(modalities=("full",), timeout_s=2.0,
                      familiarization=FamiliarizationConfig(trials=0),
                      cohort=CohortConfig(size=1, avr_experts=0, games_experts=0,
                                          both_experts=0))  # fmt: skip
    run_study(one, tmp_path / "run", workers=1)
    # The manifest names the BLAS kernel that the recorded states were computed with.
    manifest = json.loads((tmp_path / "run" / "manifest.json").read_text())
    assert manifest["blas"] == blas_description()
    assert manifest["numpy_loops"] == numpy_loops_description()
    source = load_replay(tmp_path / "run", "P01", 1)
    shown = []

    class Display:
        def show(self, frame) -> None:
            shown.append(frame)

    small = HeadCameraConfig(width_px=160, height_px=120)
    with RemoteSite(replay_site(source, small)) as site:
        assert replay(source, site, Display(), speed=0) == 61  # 2 s at 30 Hz, both ends
    trace = source.trajectory
    for frame in shown[::15]:
        row = trace[trace["time_s"] <= frame.time_s + 1e-9].iloc[-1]
        np.testing.assert_allclose(frame.arm_q_rad, row[[f"{j}_rad" for j in RIGHT_ARM_JOINTS]],
                                   atol=1e-9)  # fmt: skip
        np.testing.assert_allclose(
            frame.T_base_gripper[:3, 3],
            row[["gripper_x_m", "gripper_y_m", "gripper_z_m"]],
            atol=1e-6,
        )
        assert frame.cues.ghost and frame.cloud_points_m is not None
    with pytest.raises(RunFolderError, match=r"has no trial 9 of participant 'P01'"):
        load_replay(tmp_path / "run", "P01", 9)

"""Run-folder files survive failed writes and cut-off rows."""

from __future__ import annotations

import builtins
import os
import subprocess
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest

from arteleop.errors import RunFolderError
from arteleop.study import TRIAL_COLUMNS, RunFolder
from arteleop.study.run_folder import cell, csv_line, write_atomic


def _row(participant: str, index: int) -> dict[str, object]:
    return {
        "participant": participant, "phase": "experimental", "trial_index": index,
        "modality": "full", "position": 1, "seed": 12, "outcome": "success",
        "completion_time_s": 1 / 3, "placement_error_m": np.float64(0.0125),
        "normalized_jerk_xy": float("nan"),
        "trajectory_file": f"trajectories/{participant}/{index}.csv",
    }  # fmt: skip


def _folder(tmp_path: Path) -> RunFolder:
    folder = RunFolder(tmp_path / "run")
    folder.start("seed = 0\n", {"format_version": 1}, "participant\nP01\n")
    return folder


TRACE = {"time_s": np.array([0.0, 0.01]), "hand_x_m": np.array([np.nan, 0.25])}


def test_cells_round_trip_floats_and_leave_nan_empty() -> None:
    assert cell(1 / 3) == "0.3333333333333333" and float(cell(1 / 3)) == 1 / 3
    assert cell(np.float64(0.1)) == "0.1" and cell(np.int64(4)) == "4"
    assert cell(float("nan")) == "" and cell(None) == ""
    assert csv_line(["a,b", 1.5]) == '"a,b",1.5\n'


def test_trials_are_appended_whole_and_read_back(tmp_path: Path) -> None:
    folder = _folder(tmp_path)
    folder.append_trial(_row("P01", 2), TRACE)
    folder.append_trial(_row("P01", 1), TRACE)
    rows = folder.done_rows()
    assert list(rows) == [("P01", 2), ("P01", 1)]
    assert rows[("P01", 1)].startswith("P01,experimental,1,full,1,12,success,0.3333333333333333,")
    trace = (folder.path / "trajectories/P01/1.csv").read_text()
    assert trace == "time_s,hand_x_m\n0.0,\n0.01,0.25\n"
    folder.finish([("P01", 1), ("P01", 2)])
    assert list(folder.done_rows()) == [("P01", 1), ("P01", 2)]  # plan order
    assert folder.trials().columns.tolist() == list(TRIAL_COLUMNS)


def test_a_row_cut_short_by_a_kill_is_set_aside_on_resume(tmp_path: Path) -> None:
    folder = _folder(tmp_path)
    folder.append_trial(_row("P01", 1), TRACE)
    whole = folder.trials_path.read_bytes()
    with open(folder.trials_path, "ab") as f:
        f.write(b"P01,experimental,2,fu")  # what kill -9 can leave
    assert list(folder.done_rows()) == [("P01", 1)]  # a reader writes nothing
    assert folder.trials_path.read_bytes() == whole + b"P01,experimental,2,fu"
    assert list(folder.done_rows(repair=True)) == [("P01", 1)]
    assert folder.trials_path.read_bytes() == whole
    assert (folder.path / "trials-set-aside.csv").read_text() == "P01,experimental,2,fu\n"
    assert folder.notes == [
        f"{folder.trials_path}: line 3 was cut short; moved to "
        f"{folder.path / 'trials-set-aside.csv'}."
    ]


def test_a_write_that_fails_midway_leaves_no_half_row(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    folder = _folder(tmp_path)
    folder.append_trial(_row("P01", 1), TRACE)
    whole = folder.trials_path.read_bytes()
    real_open = builtins.open

    class HalfFull:
        """A file on a disk that fills up halfway through the write."""

        def __init__(self, f):
            self._f = f

        def __enter__(self):
            return self

        def __exit__(self, *exc):
            self._f.close()

        def tell(self):
            return self._f.tell()

        def truncate(self, size):
            return self._f.truncate(size)

        def write(self, data):
            self._f.write(data[: len(data) // 2])
            self._f.flush()
            raise OSError(28, "No space left on device")

    def fake_open(path, mode="r", *args, **kwargs):
        f = real_open(path, mode, *args, **kwargs)
        return HalfFull(f) if str(path).endswith("trials.csv") and "a" in mode else f

    monkeypatch.setattr(builtins, "open", fake_open)
    with pytest.raises(RunFolderError, match=r"Cannot add a row to .*trials.csv: No space left on "
                       r"device. The rows before it are intact"):  # fmt: skip
        folder.append_trial(_row("P01", 2), TRACE)
    monkeypatch.undo()
    assert folder.trials_path.read_bytes() == whole


@pytest.fixture
def small_disk(tmp_path: Path) -> Iterator[Path]:
    """A 64 KiB file system of its own (tmpfs), so that a write can really run out of space."""
    disk = tmp_path / "disk"
    disk.mkdir()
    if (
        os.geteuid() != 0
        or subprocess.run(
            ["mount", "-t", "tmpfs", "-o", "size=64k", "tmpfs", str(disk)], capture_output=True
        ).returncode
    ):
        pytest.skip("needs root and tmpfs to make a small disk")
    try:
        yield disk
    finally:
        subprocess.run(["umount", str(disk)], check=True)


def test_a_read_only_file_system_fails_loudly(small_disk: Path) -> None:
    subprocess.run(["mount", "-o", "remount,ro", str(small_disk)], check=True)
    with pytest.raises(
        RunFolderError, match=r"^Cannot write .*disk/run/x.csv: Read-only file system\.$"
    ):
        write_atomic(small_disk / "run" / "x.csv", "a\n")


def test_a_full_disk_leaves_the_rows_before_intact(small_disk: Path) -> None:
    folder = RunFolder(small_disk / "run")
    folder.start("seed = 0\n", {"format_version": 1}, "participant\nP01\n")
    folder.append_trial(_row("P01", 1), TRACE)
    whole = folder.trials_path.read_bytes()
    big = {"time_s": np.linspace(0.0, 1.0, 20_000)}  # ~400 KB: more than the disk holds
    with pytest.raises(RunFolderError, match=r"Cannot write .*2.csv: No space left on device"):
        folder.append_trial(_row("P01", 2), big)
    assert folder.trials_path.read_bytes() == whole
    assert sorted(p.name for p in (small_disk / "run/trajectories/P01").iterdir()) == ["1.csv"]


def test_a_read_only_folder_fails_loudly(tmp_path: Path) -> None:
    if os.geteuid() == 0:
        pytest.skip("root writes into read-only folders (the file-system test covers root)")
    locked = tmp_path / "locked"
    locked.mkdir()
    locked.chmod(0o555)
    try:
        with pytest.raises(RunFolderError, match=r"Cannot write .*locked/x.csv: Permission denied"):
            write_atomic(locked / "x.csv", "a\n")
    finally:
        locked.chmod(0o755)


def test_an_unwritable_file_fails_loudly_and_leaves_no_temporary(tmp_path: Path) -> None:
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    with pytest.raises(RunFolderError, match=r"Cannot write .*file/x.csv"):
        write_atomic(blocker / "x.csv", "a\n")
    target = tmp_path / "dir-in-the-way"
    (target).mkdir()
    with pytest.raises(RunFolderError, match=r"Cannot write .*dir-in-the-way: Is a directory"):
        write_atomic(target, "a\n")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["dir-in-the-way", "file"]


def test_a_foreign_trials_file_is_refused(tmp_path: Path) -> None:
    folder = _folder(tmp_path)
    folder.trials_path.write_text("participant,phase\nP01,experimental\n")
    with pytest.raises(RunFolderError, match=r"trials.csv line 1: expected the header"):
        folder.done_rows()


def test_written_files_get_the_umask_permissions_not_private_ones(tmp_path: Path) -> None:
    """The temporary file behind the rename is made private; the file written must not be."""
    old = os.umask(0o022)
    try:
        write_atomic(tmp_path / "a.csv", "a\n")
        os.umask(0o077)
        write_atomic(tmp_path / "b.csv", "b\n")
    finally:
        os.umask(old)
    assert (tmp_path / "a.csv").stat().st_mode & 0o777 == 0o644
    assert (tmp_path / "b.csv").stat().st_mode & 0o777 == 0o600


def test_a_private_exclusive_write_keeps_a_file_made_first(tmp_path: Path) -> None:
    """A secret (the links' key): its owner's only, whatever the umask, and written only where
    no file is yet: one another writer made first is kept, and no temporary file is left."""
    old = os.umask(0o022)
    try:
        write_atomic(tmp_path / "key", "first\n", private=True, exclusive=True)
        write_atomic(tmp_path / "key", "second\n", private=True, exclusive=True)
    finally:
        os.umask(old)
    assert (tmp_path / "key").read_text() == "first\n"
    assert (tmp_path / "key").stat().st_mode & 0o777 == 0o600
    assert [p.name for p in tmp_path.iterdir()] == ["key"]

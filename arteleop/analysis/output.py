"""A report folder written whole or not at all: into a hidden folder beside it, renamed into
place once its last file is in. A full disk or a crash leaves the old report (or none), never
half of one."""

from __future__ import annotations

import contextlib
import os
import shutil
from collections.abc import Iterator
from pathlib import Path

REPORT_MARKERS = ("report.md", "cohorts.md", "power.md")
"""A folder holding one of these (and no trials.csv) is a report arteleop wrote."""


def is_report_folder(path: Path) -> bool:
    """Whether ``path`` is a folder of a report arteleop wrote, which ``--force`` may replace."""
    path = Path(path)
    return (
        path.is_dir()
        and any((path / name).is_file() for name in REPORT_MARKERS)
        and not (path / "trials.csv").exists()
    )


@contextlib.contextmanager
def whole_folder(out_dir: Path) -> Iterator[Path]:
    """Yield a hidden folder beside ``out_dir`` to write into; when the block ends, it replaces
    ``out_dir`` (an existing one is removed only once the new one is in place). If the block
    fails, the hidden folder is removed and ``out_dir`` is left as it was."""
    out_dir = Path(out_dir)
    _remove_left_behind(out_dir)
    partial = out_dir.parent / f".{out_dir.name}.partial-{os.getpid()}"
    shutil.rmtree(partial, ignore_errors=True)
    partial.mkdir(parents=True)
    try:
        yield partial
    except BaseException:
        shutil.rmtree(partial, ignore_errors=True)
        raise
    old = out_dir.parent / f".{out_dir.name}.old-{os.getpid()}"
    if out_dir.exists():
        os.replace(out_dir, old)
    os.replace(partial, out_dir)
    shutil.rmtree(old, ignore_errors=True)


def _remove_left_behind(out_dir: Path) -> None:
    """Remove the hidden folders of ``out_dir`` that a killed writer left (its process is gone);
    a live writer's are its own."""
    for hidden in out_dir.parent.glob(f".{out_dir.name}.*-*"):
        kind, _, pid = hidden.name.rpartition("-")
        if kind.endswith((".partial", ".old")) and pid.isdigit() and not _alive(int(pid)):
            shutil.rmtree(hidden, ignore_errors=True)


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # another user's process
        return True
    return True

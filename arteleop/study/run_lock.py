"""One writer per run folder: an operating-system lock on ``RUN_DIR/.arteleop.lock``, held for the
life of a run or a resume.

The kernel releases the lock when the process that holds it dies, however it dies, so a
``kill -9`` never leaves a stale lock. A second writer is refused with the holder's process id.
Within one process the lock is re-entrant: the runner and the command around it may both take
it.
"""

from __future__ import annotations

import contextlib
import fcntl
import os
from collections.abc import Iterator
from pathlib import Path

from arteleop.errors import RunFolderError
from arteleop.study.run_folder import RunFolder

LOCK_FILE = ".arteleop.lock"

_held: dict[Path, tuple[int, int]] = {}  # resolved folder -> (file descriptor, depth)


@contextlib.contextmanager
def run_lock(folder: Path) -> Iterator[None]:
    """Hold ``folder``'s lock while the block runs; raise :class:`RunFolderError` naming the
    holder if another process has it."""
    key = Path(folder).resolve()
    if key in _held:
        fd, depth = _held[key]
        _held[key] = (fd, depth + 1)
        try:
            yield
        finally:
            fd, depth = _held[key]
            _held[key] = (fd, depth - 1)
        return
    path = key / LOCK_FILE
    try:
        fd = os.open(path, os.O_RDWR | os.O_CREAT | os.O_CLOEXEC, 0o666)
    except OSError as err:
        raise RunFolderError(f"Cannot lock {folder}: {err.strerror or err}.") from err
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except BlockingIOError:
        holder = os.pread(fd, 64, 0).decode("ascii", "replace").strip() or "unknown"
        os.close(fd)
        raise RunFolderError(
            f"{folder} is being written by another arteleop (pid {holder}): wait for it to "
            f"end, or stop it; then {RunFolder(folder).carry_on()} continues the run."
        ) from None
    os.ftruncate(fd, 0)
    os.pwrite(fd, f"{os.getpid()}\n".encode("ascii"), 0)
    _held[key] = (fd, 1)
    try:
        yield
    finally:
        fd, depth = _held.pop(key)
        os.close(fd)  # the kernel drops the lock with the last descriptor


def after_fork_in_child() -> None:
    """A forked worker holds copies of its parent's lock descriptors: closing them lets the
    lock go when the parent dies, whatever the worker does."""
    for fd, _ in _held.values():
        with contextlib.suppress(OSError):
            os.close(fd)
    _held.clear()

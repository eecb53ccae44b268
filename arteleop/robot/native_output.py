"""Silence text that PyBullet's C++ core prints straight to the process's stdout, its import
banner included."""

from __future__ import annotations

import contextlib
import ctypes
import os
import sys
from collections.abc import Iterator

_LIBC = ctypes.CDLL(None)


@contextlib.contextmanager
def native_stdout_silenced(fds: tuple[int, ...] = (1,)) -> Iterator[None]:
    """Send file descriptors ``fds`` (stdout by default) to /dev/null while the block runs, C-level
    prints included."""
    sys.stdout.flush()
    sys.stderr.flush()
    saved = [os.dup(fd) for fd in fds]
    try:
        with open(os.devnull, "wb") as devnull:
            for fd in fds:
                os.dup2(devnull.fileno(), fd)
            try:
                yield
            finally:
                # C's stdio buffers what it prints to a pipe; flush it while it still goes to
                # /dev/null, or it reaches the terminal at exit.
                _LIBC.fflush(None)
    finally:
        for fd, copy in zip(fds, saved, strict=True):
            os.dup2(copy, fd)
            os.close(copy)


# Importing this module loads PyBullet with its build-time banner kept off the user's terminal;
# the robot and scene packages import it first, and later imports find PyBullet loaded.
if "pybullet" not in sys.modules:
    with native_stdout_silenced((1, 2)):  # the banner goes to stderr
        import pybullet  # noqa: F401

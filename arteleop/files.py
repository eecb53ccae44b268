"""Writing files so that a reader never sees half of one."""

from __future__ import annotations

import contextlib
import os
import re
import tempfile
from pathlib import Path


def is_temporary(path: Path) -> bool:
    """Whether ``path`` is a temporary file of :func:`write_atomic` (``.NAME.XXXXXXXX.tmp``
    beside the file it writes): one a crash or a kill left behind holds nothing the file it
    was to become does not."""
    return re.fullmatch(r"\..+\.[a-z0-9_]{8}\.tmp", path.name) is not None


def write_atomic(path: Path, text: str, *, private: bool = False, exclusive: bool = False) -> None:
    """Write ``text`` to ``path`` through a synced temporary file beside it and a rename, so a
    reader (another process building the same cache, a crash) sees the old file or the new one.
    ``private``: readable by its owner only (a secret). ``exclusive``: only where no file is
    yet; one another writer made first is kept as it is. Raises ``OSError``; the temporary file
    is removed on failure."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        # mkstemp makes the file private (0600); a written file gets what open() would give it,
        # so a lab's run folders stay readable by the group the umask allows.
        if not private:
            umask = os.umask(0)
            os.umask(umask)
            os.fchmod(fd, 0o666 & ~umask)
        with os.fdopen(fd, "w", encoding="utf-8", newline="") as f:
            f.write(text)
            f.flush()
            os.fsync(f.fileno())
        if exclusive:
            with contextlib.suppress(FileExistsError):
                os.link(tmp, path)
            os.unlink(tmp)
        else:
            os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise
    # The rename is durable once the folder's entry is on disk.
    with contextlib.suppress(OSError):
        folder = os.open(path.parent, os.O_RDONLY)
        try:
            os.fsync(folder)
        finally:
            os.close(folder)

"""Ctrl-C: the command ends as interrupted even where a library swallowed the KeyboardInterrupt."""

from __future__ import annotations

import threading

CTRL_C = threading.Event()
"""Set by the first Ctrl-C. Some libraries turn a KeyboardInterrupt raised while they import into
an ImportError (open3d: "initialization failed"), and some swallow that in an optional-import
guard; the command still ends as interrupted."""


def on_ctrl_c(signum: int, frame: object) -> None:
    CTRL_C.set()
    raise KeyboardInterrupt


def check_ctrl_c(*_: object) -> None:
    """Raise KeyboardInterrupt if a Ctrl-C came and was swallowed on its way up."""
    if CTRL_C.is_set():
        raise KeyboardInterrupt

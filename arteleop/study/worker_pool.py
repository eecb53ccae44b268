"""The worker processes a study's trials or blocks run in: a pool of its own or the user's
executor, stopped at once on Ctrl-C, and workers that end with the process that started them."""

from __future__ import annotations

import contextlib
import os
import signal
import threading
import time
from collections.abc import Collection, Iterator
from concurrent.futures import Executor, Future, ProcessPoolExecutor
from typing import Any

from arteleop.study.run_lock import after_fork_in_child

PARENT_CHECK_S = 0.5
"""How often a worker checks that the process that started it is still there (s)."""


@contextlib.contextmanager
def worker_pool(
    executor: Executor | None, running: Collection[Future[Any]], workers: int, **options: Any
) -> Iterator[Executor]:
    """``executor``, or a pool of ``workers`` processes of its own (``options`` go to
    :class:`ProcessPoolExecutor`), each begun by :func:`start_worker`. A stop (Ctrl-C, a failed
    write) cancels the futures ``running`` and does not wait for the work under way: a pool of
    its own has its workers ended at once."""
    pool = executor or ProcessPoolExecutor(
        workers, initializer=start_worker, initargs=(os.getpid(),), **options
    )
    try:
        yield pool
    except BaseException:
        for future in running:
            future.cancel()
        if executor is None:
            stop_workers(pool)  # type: ignore[arg-type]
        raise
    finally:
        if executor is None:
            pool.shutdown(wait=True, cancel_futures=True)


def start_worker(parent_pid: int) -> None:
    """In a worker: Ctrl-C reaches the whole process group, and the parent alone handles it; the
    run folder's lock stays the parent's; and the worker ends when its parent is gone, however
    it went (a ``kill -9`` leaves no orphans blocked on a pipe)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    after_fork_in_child()
    threading.Thread(target=_exit_with_parent, args=(parent_pid,), daemon=True).start()


def _exit_with_parent(parent_pid: int) -> None:
    while os.getppid() == parent_pid:
        time.sleep(PARENT_CHECK_S)
    os._exit(1)


def stop_workers(pool: ProcessPoolExecutor) -> None:
    """End the pool's worker processes now; their trials are lost and run again on resume.
    (``ProcessPoolExecutor`` has no public way to do this before Python 3.14.)"""
    for process in list(getattr(pool, "_processes", {}).values()):
        process.terminate()

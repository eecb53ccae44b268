"""Independent seeded runs on both of the machine's cores: the suite's slowest set-ups are a
handful of whole trials, and their numbers do not depend on where they run."""

from __future__ import annotations

import multiprocessing
from collections.abc import Callable, Iterable
from concurrent.futures import ProcessPoolExecutor
from typing import Any, TypeVar

T = TypeVar("T")
WORKERS = 2


def run_each(fn: Callable[..., T], calls: Iterable[tuple[Any, ...]]) -> list[T]:
    """``[fn(*args) for args in calls]``, on :data:`WORKERS` processes, in order."""
    with ProcessPoolExecutor(WORKERS, mp_context=multiprocessing.get_context("fork")) as pool:
        futures = [pool.submit(fn, *args) for args in calls]
        return [f.result() for f in futures]

"""A trial's progress bar over simulated seconds."""

from __future__ import annotations

import contextlib
from collections.abc import Callable, Iterator
from typing import TYPE_CHECKING

from arteleop.cli.interrupt import check_ctrl_c

if TYPE_CHECKING:
    from arteleop.teleop import TrialProgress


@contextlib.contextmanager
def trial_progress(
    total_s: float, what: str, quiet: bool
) -> Iterator[Callable[[TrialProgress], None] | None]:
    """A progress bar over simulated seconds, on stderr; nothing with --quiet."""
    if quiet:
        yield check_ctrl_c
        return
    from tqdm import tqdm

    with tqdm(total=round(total_s), desc=what, unit="s simulated", leave=False) as bar:

        def update(status: TrialProgress) -> None:
            check_ctrl_c()
            if int(status.time_s) > bar.n:
                bar.update(int(status.time_s) - bar.n)

        yield update

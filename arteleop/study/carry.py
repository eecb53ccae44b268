"""What a simulated participant carries from one trial to its next, and where a run folder keeps
it: the display's lag as it believed it at the trial's end (``believed_lag_s``) and whether it
saw that it missed (``saw_miss``), the outcomes it has seen adding up over its trials
(docs/explanation/operator-model.md: the lag learnt, knowing one's misses). A person's trial
(both columns empty) carries nothing: the next trial starts from the model's defaults."""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass, field

from arteleop.analysis.data import TRIAL_COLUMNS
from arteleop.errors import RunFolderError
from arteleop.operator import SeenOutcomes


@dataclass(frozen=True)
class Carried:
    """What a simulated participant brings from its last trial to the next.

    Attributes:
        lag_s: The display's lag as it believed it at that trial's end (s).
        outcomes: The outcomes of its trials so far that it has seen, misses among them.
    """

    lag_s: float
    outcomes: SeenOutcomes = field(default_factory=SeenOutcomes)


def carried_after(before: Carried | None, lag_s: float | None, saw_miss: bool) -> Carried | None:
    """What a participant carries from a trial it ended believing the lag ``lag_s`` (s), having
    seen a miss or not, having brought ``before`` to it; None after a person's trial (``lag_s``
    None)."""
    if lag_s is None:
        return None
    seen = SeenOutcomes() if before is None else before.outcomes
    return Carried(lag_s, seen.after(saw_miss))


def row_carried(row: dict[str, object]) -> tuple[float | None, bool]:
    """A trial's row's belief of the lag at its end (s; None for a person's, NaN) and whether
    the participant saw a miss."""
    lag_s = float(row.get("believed_lag_s", math.nan))  # type: ignore[arg-type]
    return (None if math.isnan(lag_s) else lag_s), row.get("saw_miss") == 1


def line_carried(line: str, where: str) -> tuple[float | None, bool]:
    """The same from a row of trials.csv as written (``line``); ``where`` names the row in a
    :class:`RunFolderError` for a value that cannot be read."""
    row = dict(zip(TRIAL_COLUMNS, next(csv.reader([line])), strict=True))
    lag_text, saw_text = row["believed_lag_s"], row["saw_miss"]
    if lag_text == "":
        return None, False
    try:
        lag_s = float(lag_text)
    except ValueError:
        lag_s = math.nan
    again = "Correct the row or move it out of the file, then resume."
    if not 0 <= lag_s < math.inf:
        raise RunFolderError(
            f"{where}, column believed_lag_s: {lag_text!r}; expected seconds (0 or more) or "
            f"empty. {again}"
        )
    if saw_text not in ("0", "1"):
        raise RunFolderError(f"{where}, column saw_miss: {saw_text!r}; expected 0 or 1. {again}")
    return lag_s, saw_text == "1"

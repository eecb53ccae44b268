"""A run folder on disk (docs/reference/data-format.md), written so that no crash corrupts it.

- Whole files (``study.toml``, ``manifest.json``, ``participants.csv``, ``questionnaire.csv``,
  trajectories, the final ``trials.csv``) are written to a temporary file, synced, then renamed
  over the target: a reader sees the old file or the new one, never half of one.
- ``trials.csv`` grows by whole rows as trials end: each row is one write, flushed and synced;
  a write that fails is cut back off. A row that a ``kill -9`` left half-written has no line
  end; resuming sets it aside (the trial runs again).
- When every trial is in, the rows are put in plan order (participant, then trial), so the
  files of a run do not depend on which trial finished first.
- Nothing is dropped silently: a row that cannot stay in trials.csv (cut short, a duplicate, a
  trial the plan does not have) is moved to ``trials-set-aside.csv`` beside it, and the run
  says so (:attr:`RunFolder.notes`).
"""

from __future__ import annotations

import csv
import io
import json
import math
import os
from collections.abc import Iterable, Sequence
from pathlib import Path

import numpy as np
import pandas as pd

from arteleop import files
from arteleop.analysis.data import TRIAL_COLUMNS
from arteleop.errors import RunFolderError

FORMAT_VERSION = 8
"""The version of docs/reference/data-format.md that the run folder follows; the analysis reads the
same columns (``TRIAL_COLUMNS`` and the others come from it)."""

STUDY_FILE = "study.toml"
MANIFEST_FILE = "manifest.json"
TRIALS_FILE = "trials.csv"
PARTICIPANTS_FILE = "participants.csv"
QUESTIONNAIRE_FILE = "questionnaire.csv"
SET_ASIDE_FILE = "trials-set-aside.csv"


def cell(value: object) -> str:
    """A value as a CSV cell: shortest round-trip floats, empty for NaN and None."""
    if value is None:
        return ""
    if isinstance(value, bool | np.bool_):
        return "true" if value else "false"
    if isinstance(value, int | np.integer):
        return str(int(value))
    if isinstance(value, float | np.floating):
        return "" if math.isnan(value) else repr(float(value))
    return str(value)


def csv_line(values: Iterable[object]) -> str:
    """One CSV line, line end included."""
    buffer = io.StringIO()
    csv.writer(buffer, lineterminator="\n").writerow([cell(v) for v in values])
    return buffer.getvalue()


def write_atomic(path: Path, text: str, *, private: bool = False, exclusive: bool = False) -> None:
    """:func:`arteleop.files.write_atomic`, failing with a :class:`RunFolderError` that names
    the file."""
    try:
        files.write_atomic(path, text, private=private, exclusive=exclusive)
    except OSError as err:
        raise RunFolderError(f"Cannot write {path}: {err.strerror or err}.") from err


def table_text(columns: Sequence[str], rows: Iterable[Sequence[object]]) -> str:
    """A whole CSV file: header and rows."""
    return csv_line(columns) + "".join(csv_line(row) for row in rows)


def trace_text(trace: dict[str, np.ndarray]) -> str:
    """A trajectory file: one row per control tick."""
    columns = list(trace)
    return table_text(columns, zip(*(trace[c].tolist() for c in columns), strict=True))


REAL = "real"
"""A run folder's ``cohort`` (manifest.json) when people take part (``arteleop study serve``)."""


class RunFolder:
    """The files of one study run, in ``path``."""

    def __init__(self, path: Path) -> None:
        self.path = Path(path)
        self.notes: list[str] = []
        """What the folder set aside or repaired, for the user to be told."""

    @property
    def trials_path(self) -> Path:
        return self.path / TRIALS_FILE

    def is_run_folder(self) -> bool:
        return (self.path / STUDY_FILE).is_file() and (self.path / MANIFEST_FILE).is_file()

    def manifest(self) -> dict[str, object]:
        path = self.path / MANIFEST_FILE
        try:
            manifest = json.loads(path.read_text(encoding="utf-8"))
        except (OSError, UnicodeDecodeError, json.JSONDecodeError) as err:
            raise RunFolderError(f"Cannot read {path}: {err}.") from err
        if not isinstance(manifest, dict):
            raise RunFolderError(
                f"{path}: a JSON {type(manifest).__name__}, expected an object with the run's "
                "format_version, seed and packages; restore it from a backup."
            )
        return manifest

    def carry_on(self) -> str:
        """The command that continues this run: ``study serve`` for a run served to people
        (``cohort`` real in the manifest), else ``study resume``."""
        try:
            served = self.manifest().get("cohort") == REAL
        except RunFolderError:
            served = False
        if served:
            return f"'arteleop study serve --out {self.path}'"
        return f"'arteleop study resume {self.path}'"

    def report_finished(self) -> bool:
        """Whether the run's report was written whole (``report_finished`` in the manifest)."""
        return bool(self.manifest().get("report_finished"))

    def mark_report_finished(self, when: str) -> None:
        manifest = self.manifest()
        manifest["report_finished"] = when
        self.write_manifest(manifest)

    def write_manifest(self, manifest: dict[str, object]) -> None:
        write_atomic(self.path / MANIFEST_FILE, json.dumps(manifest, indent=2) + "\n")

    def start(self, study_text: str, manifest: dict[str, object], participants: str) -> None:
        """A new run: the definition, the manifest, the participants and an empty trials.csv.
        Files are written in that order, the manifest last but one, so that a folder with a
        manifest has its definition."""
        write_atomic(self.path / STUDY_FILE, study_text)
        write_atomic(self.path / PARTICIPANTS_FILE, participants)
        write_atomic(self.trials_path, csv_line(TRIAL_COLUMNS))
        self.write_manifest(manifest)

    def done_rows(self, repair: bool = False) -> dict[tuple[str, int], str]:
        """The rows in trials.csv, by (participant, trial_index), as their exact lines.

        A last line without a line end is a row whose write was cut short when it lacks
        fields (its trial runs again), or a whole row that lost its line end (an editor). A
        second row of a trial does not count. With ``repair`` (the writer, holding the lock),
        the whole row gets its line end back and the others are set aside; without, nothing
        is written."""
        path = self.trials_path
        try:
            data = path.read_bytes()
        except OSError as err:
            raise RunFolderError(f"Cannot read {path}: {err.strerror or err}.") from err
        try:
            text = data.decode("utf-8")
        except UnicodeDecodeError as err:
            raise RunFolderError(
                f"{path}: not UTF-8 text (byte {err.start}); restore it from a backup."
            ) from None
        lines = text.splitlines(keepends=True)
        if not lines or next(csv.reader([lines[0]])) != list(TRIAL_COLUMNS):
            raise RunFolderError(
                f"{path} line 1: expected the header {','.join(TRIAL_COLUMNS)}; this is not a "
                "trials file that arteleop started."
            )
        if not lines[-1].endswith("\n"):
            last = len(lines)
            if self._whole_row(next(csv.reader([lines[-1]]))):
                lines[-1] += "\n"
                if repair:
                    self._rewrite_trials(lines)
                    self.notes.append(f"{path} line {last}: a whole row without its line end; "
                                      "the line end is back.")  # fmt: skip
            else:
                cut = lines.pop()
                if repair:
                    self.set_aside([cut], f"line {last} was cut short")
                    self._rewrite_trials(lines)
        rows: dict[tuple[str, int], str] = {}
        twice: list[str] = []
        for number, line in enumerate(lines[1:], start=2):
            fields = next(csv.reader([line]))
            if len(fields) != len(TRIAL_COLUMNS):
                raise RunFolderError(
                    f"{path} line {number}: {len(fields)} fields, expected {len(TRIAL_COLUMNS)}."
                )
            try:
                key = (fields[0], int(fields[2]))
            except ValueError:
                raise RunFolderError(
                    f"{path} line {number}, column trial_index: {fields[2]!r}; expected a whole "
                    "number. Correct the row or move it out of the file, then resume."
                ) from None
            if key in rows:
                twice.append(line)
            else:
                rows[key] = line
        if twice and repair:
            self.set_aside(twice, f"{len(twice)} second row(s) of a trial already in it")
            self._rewrite_trials([lines[0], *rows.values()])
        lost = {key: line for key, line in rows.items() if self._trajectory_lost(line)}
        if lost:  # a trial's record is its row and its trajectory: it runs again
            rows = {key: line for key, line in rows.items() if key not in lost}
            if repair:
                self.set_aside(list(lost.values()), f"{len(lost)} row(s) whose trajectory file "
                               "is missing, whose trials run again")  # fmt: skip
                self._rewrite_trials([lines[0], *rows.values()])
        return rows

    def _trajectory_lost(self, line: str) -> bool:
        name = next(csv.reader([line]))[TRIAL_COLUMNS.index("trajectory_file")]
        return bool(name) and not (self.path / name).is_file()

    def _whole_row(self, fields: list[str]) -> bool:
        """A row with every field, down to its trajectory file's whole name (the last field,
        the file written before the row)."""
        if len(fields) != len(TRIAL_COLUMNS):
            return False
        row = dict(zip(TRIAL_COLUMNS, fields, strict=True))
        name = f"trajectories/{row['participant']}/{row['trial_index']}.csv"
        return row["trajectory_file"] == name and (self.path / name).is_file()

    def remove_cut_writes(self) -> None:
        """Remove the temporary files of writes a kill cut short (the writer, holding the
        lock): each file they were to replace is whole, or absent and written again."""
        for path in self.path.rglob(".*.tmp"):
            if files.is_temporary(path):
                path.unlink(missing_ok=True)

    def set_aside(self, lines: Sequence[str], why: str) -> None:
        """Move ``lines`` of trials.csv to :data:`SET_ASIDE_FILE` (appended, whole lines) and
        say so in :attr:`notes`."""
        aside = self.path / SET_ASIDE_FILE
        text = "".join(line if line.endswith("\n") else line + "\n" for line in lines)
        try:
            old = aside.read_text(encoding="utf-8") if aside.exists() else ""
        except OSError as err:
            raise RunFolderError(f"Cannot read {aside}: {err.strerror or err}.") from err
        write_atomic(aside, old + text)
        self.notes.append(f"{self.trials_path}: {why}; moved to {aside}.")

    def _rewrite_trials(self, lines: Sequence[str]) -> None:
        write_atomic(self.trials_path, "".join(lines))

    def append_trial(self, row: dict[str, object], trace: dict[str, np.ndarray]) -> None:
        """A finished trial: its trajectory file, then its row of trials.csv."""
        write_atomic(self.path / str(row["trajectory_file"]), trace_text(trace))
        line = csv_line(row.get(c) for c in TRIAL_COLUMNS).encode("utf-8")
        path = self.trials_path
        try:
            with open(path, "ab") as f:
                size = f.tell()
                try:
                    f.write(line)
                    f.flush()
                    os.fsync(f.fileno())
                except OSError:
                    f.truncate(size)  # never leave half a row
                    raise
        except OSError as err:
            raise RunFolderError(
                f"Cannot add a row to {path}: {err.strerror or err}. The rows before it are "
                f"intact; free space or fix permissions, then {self.carry_on()}."
            ) from err

    def finish(self, order: Sequence[tuple[str, int]]) -> None:
        """Every trial is in: its rows in plan order; a row of a trial the plan does not have is
        set aside."""
        rows = self.done_rows(repair=True)
        missing = [key for key in order if key not in rows]
        if missing:
            raise RunFolderError(
                f"{self.trials_path} lacks {len(missing)} planned trials, the first "
                f"{missing[0][0]} trial {missing[0][1]}."
            )
        planned = set(order)
        unplanned = [line for key, line in rows.items() if key not in planned]
        if unplanned:
            self.set_aside(unplanned, f"{len(unplanned)} row(s) of trials the plan does not have")
        write_atomic(self.trials_path, csv_line(TRIAL_COLUMNS) + "".join(rows[k] for k in order))

    def write_questionnaire(self, text: str) -> None:
        write_atomic(self.path / QUESTIONNAIRE_FILE, text)

    def trials(self) -> pd.DataFrame:
        """trials.csv as a table."""
        return pd.read_csv(self.trials_path, keep_default_na=True)


def read_table(path: Path, columns: tuple[str, ...] | None) -> list[list[str]]:
    """A CSV's rows, header first, each checked to have the header's fields; the header must
    be ``columns`` when given."""
    try:
        with open(path, newline="", encoding="utf-8") as f:
            rows = [row for row in csv.reader(f) if row]
    except FileNotFoundError:
        raise RunFolderError(f"{path}: no such file.") from None
    except (OSError, UnicodeDecodeError) as err:
        raise RunFolderError(f"{path}: cannot read it ({err}).") from err
    if not rows:
        raise RunFolderError(f"{path} is empty; expected a header line.")
    if columns is not None and tuple(rows[0]) != columns:
        raise RunFolderError(
            f"{path} line 1: header {','.join(rows[0])}; expected {','.join(columns)}."
        )
    for number, row in enumerate(rows[1:], start=2):
        if len(row) != len(rows[0]):
            raise RunFolderError(
                f"{path} line {number}: {len(row)} fields, expected {len(rows[0])}."
            )
    return rows

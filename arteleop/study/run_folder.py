"""A run folder on disk (docs/data-format.md), written so that no crash corrupts it.

- Whole files (``study.toml``, ``manifest.json``, ``participants.csv``, ``questionnaire.csv``,
  trajectories, the final ``trials.csv``) are written to a temporary file, synced, then renamed
  over the target: a reader sees the old file or the new one, never half of one.
- ``trials.csv`` grows by whole rows as trials end: each row is one write, flushed and synced;
  a write that fails is cut back off. A row that a ``kill -9`` left half-written has no line
  end, and resuming drops it (the trial runs again).
- When every trial is in, the rows are put in plan order (participant, then trial), so the
  files of a run do not depend on which trial finished first.
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

FORMAT_VERSION = 4
"""The version of docs/data-format.md that the run folder follows; the analysis reads the same
columns (``TRIAL_COLUMNS`` and the others come from it)."""

STUDY_FILE = "study.toml"
MANIFEST_FILE = "manifest.json"
TRIALS_FILE = "trials.csv"
PARTICIPANTS_FILE = "participants.csv"
QUESTIONNAIRE_FILE = "questionnaire.csv"


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


def write_atomic(path: Path, text: str) -> None:
    """:func:`arteleop.files.write_atomic`, failing with a :class:`RunFolderError` that names
    the file."""
    try:
        files.write_atomic(path, text)
    except OSError as err:
        raise RunFolderError(f"Cannot write {path}: {err.strerror or err}.") from err


def table_text(columns: Sequence[str], rows: Iterable[Sequence[object]]) -> str:
    """A whole CSV file: header and rows."""
    return csv_line(columns) + "".join(csv_line(row) for row in rows)


def trace_text(trace: dict[str, np.ndarray]) -> str:
    """A trajectory file: one row per control tick."""
    columns = list(trace)
    return table_text(columns, zip(*(trace[c].tolist() for c in columns), strict=True))


class RunFolder:
    """The files of one study run, in ``path``."""

    def __init__(self, path: Path) -> None:
        self.path = Path(path)

    @property
    def trials_path(self) -> Path:
        return self.path / TRIALS_FILE

    def is_run_folder(self) -> bool:
        return (self.path / STUDY_FILE).is_file() and (self.path / MANIFEST_FILE).is_file()

    def manifest(self) -> dict[str, object]:
        path = self.path / MANIFEST_FILE
        try:
            return json.loads(path.read_text(encoding="utf-8"))
        except (OSError, json.JSONDecodeError) as err:
            raise RunFolderError(f"Cannot read {path}: {err}.") from err

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

    def done_rows(self) -> dict[tuple[str, int], str]:
        """The rows in trials.csv, by (participant, trial_index), as their exact lines. A last
        line without a line end (a write cut short) is cut off the file first."""
        path = self.trials_path
        try:
            data = path.read_bytes()
        except OSError as err:
            raise RunFolderError(f"Cannot read {path}: {err.strerror or err}.") from err
        if not data.endswith(b"\n"):
            keep = data.rfind(b"\n") + 1
            with open(path, "r+b") as f:
                f.truncate(keep)
                f.flush()
                os.fsync(f.fileno())
            data = data[:keep]
        lines = data.decode("utf-8").splitlines(keepends=True)
        if not lines or next(csv.reader([lines[0]])) != list(TRIAL_COLUMNS):
            raise RunFolderError(
                f"{path} line 1: expected the header {','.join(TRIAL_COLUMNS)}; this is not a "
                "trials file that arteleop started."
            )
        rows: dict[tuple[str, int], str] = {}
        for number, line in enumerate(lines[1:], start=2):
            fields = next(csv.reader([line]))
            if len(fields) != len(TRIAL_COLUMNS):
                raise RunFolderError(
                    f"{path} line {number}: {len(fields)} fields, expected {len(TRIAL_COLUMNS)}."
                )
            rows[(fields[0], int(fields[2]))] = line
        return rows

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
                "intact; free space or fix permissions, then 'arteleop study resume "
                f"{self.path}'."
            ) from err

    def finish(self, order: Sequence[tuple[str, int]]) -> None:
        """Every trial is in: its rows in plan order."""
        rows = self.done_rows()
        missing = [key for key in order if key not in rows]
        if missing:
            raise RunFolderError(
                f"{self.trials_path} lacks {len(missing)} planned trials, the first "
                f"{missing[0][0]} trial {missing[0][1]}."
            )
        write_atomic(self.trials_path, csv_line(TRIAL_COLUMNS) + "".join(rows[k] for k in order))

    def write_questionnaire(self, text: str) -> None:
        write_atomic(self.path / QUESTIONNAIRE_FILE, text)

    def trials(self) -> pd.DataFrame:
        """trials.csv as a table."""
        return pd.read_csv(self.trials_path, keep_default_na=True)

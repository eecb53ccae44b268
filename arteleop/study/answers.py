"""Real questionnaire answers merged into a run folder (``arteleop study answer``)."""

from __future__ import annotations

import csv
from pathlib import Path

from arteleop.analysis.data import AR_CLASSES, QUESTIONNAIRE_COLUMNS
from arteleop.analysis.data import QUESTIONNAIRE_ITEMS as ITEMS
from arteleop.errors import RunFolderError
from arteleop.study.run_folder import (
    PARTICIPANTS_FILE,
    QUESTIONNAIRE_FILE,
    RunFolder,
    table_text,
    write_atomic,
)
from arteleop.study.run_lock import run_lock


def merge_answers(run_dir: Path, answers: Path) -> list[str]:
    """Replace the answers of the participants in ``answers`` (a CSV with the columns of
    questionnaire.csv) in the run's questionnaire.csv; returns those participants' ids. Every
    row is checked before anything is written."""
    folder = RunFolder(run_dir)
    if not folder.is_run_folder():
        raise RunFolderError(f"{folder.path} is not a run folder (no study.toml and manifest).")
    people = [row[0] for row in _rows(folder.path / PARTICIPANTS_FILE, None)[1:]]
    new = _rows(answers, QUESTIONNAIRE_COLUMNS)[1:]
    if not new:
        raise RunFolderError(f"{answers}: no answers below the header.")
    for line, (pid, ar_class, item, score) in enumerate(new, start=2):
        problem = None
        if pid not in people:
            problem = f"participant {pid!r} is not in {PARTICIPANTS_FILE}"
        elif ar_class not in AR_CLASSES:
            problem = f"ar_class {ar_class!r}; expected one of {', '.join(AR_CLASSES)}"
        elif item not in ITEMS:
            problem = f"item {item!r}; expected one of {', '.join(ITEMS)}"
        elif score not in [str(k) for k in range(1, 8)]:
            problem = f"score {score!r}; expected a whole number 1-7"
        if problem:
            raise RunFolderError(f"{answers} line {line}: {problem}. Nothing was merged.")
    replaced = sorted({row[0] for row in new}, key=people.index)
    path = folder.path / QUESTIONNAIRE_FILE
    with run_lock(folder.path):  # not while a run or a resume writes the folder
        old = _rows(path, QUESTIONNAIRE_COLUMNS)[1:] if path.exists() else []
        kept = [row for row in old if row[0] not in replaced]

        def place(row: list[str]) -> tuple[int, int, int]:
            return people.index(row[0]), AR_CLASSES.index(row[1]), ITEMS.index(row[2])

        rows = sorted(kept + new, key=place)
        write_atomic(path, table_text(QUESTIONNAIRE_COLUMNS, rows))
    return replaced


def _rows(path: Path, columns: tuple[str, ...] | None) -> list[list[str]]:
    """A CSV's rows, header first; the header must be ``columns`` when given."""
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

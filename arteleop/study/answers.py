"""Real questionnaire answers merged into a run folder (``arteleop study answer``)."""

from __future__ import annotations

from pathlib import Path

from arteleop.analysis.data import AR_CLASSES, QUESTIONNAIRE_COLUMNS
from arteleop.errors import RunFolderError
from arteleop.study.run_folder import (
    PARTICIPANTS_FILE,
    QUESTIONNAIRE_FILE,
    STUDY_FILE,
    RunFolder,
    read_table,
    table_text,
    write_atomic,
)
from arteleop.study.run_lock import run_lock
from arteleop.study.study_file import parse_study


def merge_answers(run_dir: Path, answers: Path) -> list[str]:
    """Replace the answers of the participants in ``answers`` (a CSV with the columns of
    questionnaire.csv) in the run's questionnaire.csv; returns those participants' ids. Every
    row is checked before anything is written."""
    folder = RunFolder(run_dir)
    if not folder.is_run_folder():
        raise RunFolderError(f"{folder.path} is not a run folder (no study.toml and manifest).")
    people = [row[0] for row in read_table(folder.path / PARTICIPANTS_FILE, None)[1:]]
    items = _items(folder.path / STUDY_FILE)
    new = read_table(answers, QUESTIONNAIRE_COLUMNS)[1:]
    if not new:
        raise RunFolderError(f"{answers}: no answers below the header.")
    for line, (pid, ar_class, item, score) in enumerate(new, start=2):
        problem = None
        if pid not in people:
            problem = f"participant {pid!r} is not in {PARTICIPANTS_FILE}"
        elif ar_class not in AR_CLASSES:
            problem = f"ar_class {ar_class!r}; expected one of {', '.join(AR_CLASSES)}"
        elif item not in items:
            problem = f"item {item!r}; expected one of the study's {', '.join(items)}"
        elif score not in [str(k) for k in range(1, 8)]:
            problem = f"score {score!r}; expected a whole number 1-7"
        if problem:
            raise RunFolderError(f"{answers} line {line}: {problem}. Nothing was merged.")
    replaced = sorted({row[0] for row in new}, key=people.index)
    path = folder.path / QUESTIONNAIRE_FILE
    with run_lock(folder.path):  # not while a run or a resume writes the folder
        old = read_table(path, QUESTIONNAIRE_COLUMNS)[1:] if path.exists() else []
        kept = [row for row in old if row[0] not in replaced]

        def place(row: list[str]) -> tuple[int, int, int]:
            return people.index(row[0]), AR_CLASSES.index(row[1]), items.index(row[2])

        rows = sorted(kept + new, key=place)
        write_atomic(path, table_text(QUESTIONNAIRE_COLUMNS, rows))
    return replaced


def _items(study_path: Path) -> list[str]:
    """The ids of the questionnaire's items in the run's study file."""
    try:
        text = study_path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as err:
        raise RunFolderError(f"Cannot read {study_path}: {err}.") from None
    return [item.id for item in parse_study(text, str(study_path)).questionnaire]

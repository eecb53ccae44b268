"""Reading and checking study files (docs/reference/data-format.md). Every error names file, line,
column."""

from __future__ import annotations

import difflib
import json
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from arteleop.analysis.errors import AnalysisInputError

MODALITIES: tuple[str, ...] = ("none", "manipulation", "embodiment", "task", "full")
"""The original study's modalities, compared by the thesis's tests (docs/explanation/study.md
§3)."""
CUE_NAMES: tuple[str, ...] = (
    *MODALITIES, "predictive", "ghost", "beam", "distance_bar", "grip_bar", "target_mesh",
    "predictive_ghost",
)  # fmt: skip
"""What a ``modality`` cell may name: a modality, or modalities and AR layers joined by '+'."""
MEASURES: tuple[str, ...] = (
    "completion_time_s", "placement_error_m", "normalized_jerk_xy", "ldlj_xy", "sparc_xy",
    "submovements_xy",
)  # fmt: skip
SMOOTHNESS: tuple[str, ...] = ("normalized_jerk_xy", "ldlj_xy", "sparc_xy", "submovements_xy")
"""The smoothness measures, each of the hand in the x-y plane from motion onset to the end."""
PHASES = ("familiarization", "experimental")
OUTCOMES = (
    "success", "timeout", "tracking_lost", "dropped", "not_grasped", "operator_stopped",
    "interrupted", "failure",
)  # fmt: skip
"""How a trial may end: success, or a failure (``failure`` for a lab's own reason)."""
AR_CLASSES = ("embodiment", "manipulation", "task")
QUESTIONNAIRE_ITEMS = ("presence", "embodiment", "ease")
"""The original study's questionnaire items; a study may ask its own."""
ITEM_ID = re.compile(r"[a-z][a-z0-9_]{0,31}")
"""A questionnaire item's id: lower-case letters, digits and underscores, a letter first, at
most 32."""

TRIAL_COLUMNS = (
    "participant", "phase", "trial_index", "modality", "position", "seed", "outcome",
    "completion_time_s", "placement_error_m", "placement_error_true_m", "normalized_jerk_xy",
    "ldlj_xy", "sparc_xy", "submovements_xy", "idle_share_xy", "grasp_attempts",
    "hand_path_length_m", "latency_median_ms", "colocation_error_px", "colocation_error_m",
    "round_trip_ms", "jitter_ms", "loss", "believed_lag_s", "saw_miss", "trajectory_file",
)  # fmt: skip
NETWORK_COLUMNS = ("round_trip_ms", "jitter_ms", "loss")
"""A trial's network profile; empty reads as none (0)."""
TRIAL_REQUIRED = (
    "participant", "phase", "modality", "position", "outcome", "completion_time_s",
    "placement_error_m",
)  # fmt: skip
SUCCESS_ONLY = ("completion_time_s", "placement_error_m")
"""Required columns that a failed trial leaves empty: it has no completion time or placement."""
TRIAL_NUMERIC = (
    "trial_index", "position", "seed", "completion_time_s", "placement_error_m",
    "placement_error_true_m", "normalized_jerk_xy", "ldlj_xy", "sparc_xy", "submovements_xy",
    "idle_share_xy", "grasp_attempts", "hand_path_length_m", "latency_median_ms",
    "colocation_error_px", "colocation_error_m", "round_trip_ms", "jitter_ms", "loss",
    "believed_lag_s", "saw_miss",
)  # fmt: skip
PARTICIPANT_COLUMNS = (
    "participant", "age", "gender", "handedness", "avr_experience", "avr_hours",
    "games_experience", "games_hours", "source",
)  # fmt: skip
PARTICIPANT_NUMERIC = ("age", "avr_experience", "avr_hours", "games_experience", "games_hours")
QUESTIONNAIRE_COLUMNS = ("participant", "ar_class", "item", "score")
TRAJECTORY_COLUMNS = ("time_s", "hand_x_m", "hand_y_m", "hand_z_m")


@dataclass(frozen=True)
class StudyData:
    """A study's tables after checking.

    Attributes:
        trials: Every trial row; numeric columns are floats (NaN where empty).
        participants: Participant table, or None if not given.
        questionnaire: Questionnaire table, or None if not given.
        base_dir: Folder that ``trajectory_file`` paths are relative to.
        trials_path: Where the trials came from.
    """

    trials: pd.DataFrame
    participants: pd.DataFrame | None
    questionnaire: pd.DataFrame | None
    base_dir: Path
    trials_path: Path

    def analysed_trials(self) -> pd.DataFrame:
        """Experimental trials whose outcome is ``success``."""
        t = self.trials
        return t[(t["phase"] == "experimental") & (t["outcome"] == "success")].copy()

    @property
    def sources(self) -> tuple[str, ...]:
        """Who the participants are, as their table says (``real``, ``synthetic``), sorted;
        empty where it does not say."""
        return sources_in(self.participants)


def sources_in(table: pd.DataFrame | None) -> tuple[str, ...]:
    """The participant sources (``real``, ``synthetic``) a table's ``source`` column names,
    sorted; empty without the table, the column or a value."""
    if table is None or "source" not in table:
        return ()
    return tuple(sorted({str(v) for v in table["source"] if isinstance(v, str) and v}))


def load_study(path: Path, participants_path: Path | None = None) -> StudyData:
    """Load a run folder (trials.csv and optional participants.csv, questionnaire.csv) or a bare
    trials CSV (with ``participants_path`` if given)."""
    path = Path(path)
    if path.is_dir():
        for name in ("trials.csv", "participants.csv", "questionnaire.csv"):
            if (path / name).is_symlink():
                raise AnalysisInputError(
                    f"{path / name}: a symbolic link; a run folder's tables are read only as "
                    "files in it (a link could put another file's lines into a message): copy "
                    "the file itself into the folder"
                )
        trials_path = path / "trials.csv"
        base = path
        participants_path = participants_path or _optional(path / "participants.csv")
        questionnaire_path = _optional(path / "questionnaire.csv")
    else:
        trials_path, base, questionnaire_path = path, path.parent, None
    if not trials_path.is_file():
        if (read_manifest(base) or {}).get("task") == "pointing":
            raise AnalysisInputError(
                f"{base}: a pointing study with no trial ended yet: its pointing.csv is written "
                "as its trials end (a simulated run's once every block is in)"
            )
        raise AnalysisInputError(f"{trials_path}: no such file; a run folder holds trials.csv")
    trials = read_table(
        trials_path, TRIAL_COLUMNS, TRIAL_REQUIRED, TRIAL_NUMERIC,
        {"phase": PHASES, "outcome": OUTCOMES}, may_be_empty=SUCCESS_ONLY,
    )  # fmt: skip
    if trials.empty:
        raise AnalysisInputError(f"{trials_path}: no trials below the header")
    _check_trials(trials_path, trials, base)
    trials[list(NETWORK_COLUMNS)] = trials[list(NETWORK_COLUMNS)].fillna(0.0)
    participants = None
    if participants_path is not None:
        participants = read_table(
            participants_path, PARTICIPANT_COLUMNS, ("participant",), PARTICIPANT_NUMERIC,
            {"source": ("synthetic", "real", "")},
        )  # fmt: skip
        _check_range(participants_path, participants, "age", 0, 120)
        _check_range(participants_path, participants, "avr_hours", 1, 3)
        _check_range(participants_path, participants, "games_hours", 1, 3)
    questionnaire = None
    if questionnaire_path is not None:
        questionnaire = read_table(
            questionnaire_path, QUESTIONNAIRE_COLUMNS, QUESTIONNAIRE_COLUMNS, ("score",),
            {"ar_class": AR_CLASSES},
        )  # fmt: skip
        _check_range(questionnaire_path, questionnaire, "score", 1, 7)
        bad = ~questionnaire["item"].map(ITEM_ID.fullmatch).astype(bool)
        if bad.any():
            i = int(np.flatnonzero(bad.to_numpy())[0])
            raise AnalysisInputError(
                f"{questionnaire_path}, line {i + 2}, column item: "
                f"'{questionnaire['item'].iloc[i]}' is not an item id: expected lower-case "
                "letters, digits and _, a letter first, at most 32"
            )
    return StudyData(trials, participants, questionnaire, base, trials_path)


def read_table(
    path: Path,
    known: Sequence[str],
    required: Sequence[str],
    numeric: Sequence[str],
    categories: Mapping[str, Sequence[str]],
    may_be_empty: Sequence[str] = (),
) -> pd.DataFrame:
    """Read a CSV as text, check its columns and values, convert the numeric columns.

    A ``required`` column must be in the header and, unless in ``may_be_empty``, filled on
    every line."""
    try:
        df = pd.read_csv(path, dtype=str, keep_default_na=False, skipinitialspace=True)
    except (OSError, pd.errors.ParserError, pd.errors.EmptyDataError) as err:
        raise AnalysisInputError(f"{path}: cannot be read as CSV ({err})") from None
    except UnicodeDecodeError:
        raise AnalysisInputError(f"{path}: not UTF-8 text; save it as UTF-8 CSV") from None
    df.columns = [c.strip() for c in df.columns]
    for column in df.columns:
        if column not in known:
            close = difflib.get_close_matches(column, known, n=1)
            hint = f" Did you mean '{close[0]}'?" if close else ""
            raise AnalysisInputError(
                f"{path}, line 1: unknown column '{column}'.{hint} "
                f"Known columns: {', '.join(known)}"
            )
    missing = [c for c in required if c not in df.columns]
    if missing:
        raise AnalysisInputError(f"{path}, line 1: missing required column(s) {', '.join(missing)}")
    for column in known:
        if column not in df.columns:
            df[column] = ""
    df = df[list(known)].apply(lambda s: s.str.strip())
    for column in required:
        if column in may_be_empty:
            continue
        empty = np.flatnonzero(df[column].to_numpy() == "")
        if len(empty):
            raise AnalysisInputError(
                f"{path}, line {empty[0] + 2}, column {column}: empty, but the column is required"
            )
    for column, allowed in categories.items():
        bad = ~df[column].isin(allowed) & (df[column] != "")
        if bad.any():
            i = int(np.flatnonzero(bad.to_numpy())[0])
            raise AnalysisInputError(
                f"{path}, line {i + 2}, column {column}: unknown value '{df[column].iloc[i]}'. "
                f"Expected one of: {', '.join(a for a in allowed if a)}"
            )
    for column in numeric:
        values = pd.to_numeric(df[column].replace("", np.nan), errors="coerce")
        bad = (values.isna() | np.isinf(values)) & (df[column] != "")
        if bad.any():
            i = int(np.flatnonzero(bad.to_numpy())[0])
            kind = "a finite number" if np.isinf(values.iloc[i]) else "a number"
            raise AnalysisInputError(
                f"{path}, line {i + 2}, column {column}: '{df[column].iloc[i]}' is not {kind}"
            )
        df[column] = values.astype(float)
    return df


def load_trajectory(path: Path) -> pd.DataFrame:
    """A trajectory file: at least time_s, hand_x_m, hand_y_m, hand_z_m."""
    if not path.is_file():
        raise AnalysisInputError(f"{path}: trajectory file not found")
    try:
        df = pd.read_csv(path)
    except (OSError, UnicodeDecodeError, pd.errors.ParserError, pd.errors.EmptyDataError) as err:
        raise AnalysisInputError(f"{path}: cannot be read as CSV ({err})") from None
    missing = [c for c in TRAJECTORY_COLUMNS if c not in df.columns]
    if missing:
        raise AnalysisInputError(f"{path}, line 1: missing column(s) {', '.join(missing)}")
    return df


def _optional(path: Path) -> Path | None:
    return path if path.is_file() else None


def network_label(round_trip_ms: float, jitter_ms: float = 0.0, loss: float = 0.0) -> str:
    """A network profile's name in tables: ``250ms``, ``250ms~20ms-0.05loss``."""
    label = f"{round_trip_ms:g}ms"
    if jitter_ms:
        label += f"~{jitter_ms:g}ms"
    if loss:
        label += f"-{loss:g}loss"
    return label


def _check_trials(path: Path, trials: pd.DataFrame, base_dir: Path) -> None:
    for i, label in trials["modality"].items():
        unknown = [part for part in label.split("+") if part not in CUE_NAMES]
        if unknown:
            raise AnalysisInputError(
                f"{path}, line {i + 2}, column modality: unknown value '{label}'. Expected one "
                f"of: {', '.join(MODALITIES)}, predictive; or modalities and AR layers joined "
                f"by '+' ({', '.join(CUE_NAMES[len(MODALITIES) + 1 :])})"
            )
    exp = trials[trials["phase"] == "experimental"].fillna({c: 0.0 for c in NETWORK_COLUMNS})
    conditions = max(5, len(exp[["modality", *NETWORK_COLUMNS]].drop_duplicates()))
    bad_pos = exp[
        (exp["position"] < 1) | (exp["position"] > conditions) | (exp["position"] % 1 != 0)
    ]
    if len(bad_pos):
        i = bad_pos.index[0]
        raise AnalysisInputError(
            f"{path}, line {i + 2}, column position: {trials['position'][i]:g}; expected a whole "
            f"number from 1 to {conditions}, the study's count of conditions"
        )
    cell = ["participant", "modality", *NETWORK_COLUMNS]
    dup = exp[exp.duplicated(cell, keep=False)]
    if len(dup):
        first = dup.iloc[0]
        same = (dup["participant"] == first["participant"]) & (dup["modality"] == first["modality"])
        lines = [str(i + 2) for i in dup.index[same]]
        raise AnalysisInputError(
            f"{path}, lines {', '.join(lines)}: participant '{first['participant']}' has "
            f"{len(lines)} experimental trials in modality '{first['modality']}' under the "
            "same network profile; the design has one."
        )
    success = trials["outcome"] == "success"
    for column in SUCCESS_ONLY:
        empty = trials[success & trials[column].isna()]
        if len(empty):
            i = empty.index[0]
            raise AnalysisInputError(
                f"{path}, line {i + 2}, column {column}: empty, but a successful trial has one"
            )
    inside = base_dir.resolve()
    for i, name in trials["trajectory_file"].items():
        if name and inside not in (inside / name).resolve().parents:
            raise AnalysisInputError(
                f"{path}, line {i + 2}, column trajectory_file: '{name}' is outside the "
                "folder of the trials file; a trajectory file's path is relative to it, inside "
                "it (trajectories/P01/1.csv)"
            )
    for column in ("completion_time_s", "placement_error_m"):
        neg = trials[trials[column] < 0]
        if len(neg):
            i = neg.index[0]
            raise AnalysisInputError(
                f"{path}, line {i + 2}, column {column}: {trials[column][i]:g} is negative"
            )


def _check_range(path: Path, df: pd.DataFrame, column: str, lo: float, hi: float) -> None:
    bad = df[column].notna() & ~df[column].between(lo, hi)
    if bad.any():
        i = int(np.flatnonzero(bad.to_numpy())[0])
        raise AnalysisInputError(
            f"{path}, line {i + 2}, column {column}: {df[column].iloc[i]:g}; "
            f"expected {lo:g} to {hi:g}"
        )


def questionnaire_items(questionnaire: pd.DataFrame) -> list[str]:
    """The items a questionnaire table rates, in the order they first appear."""
    return list(dict.fromkeys(questionnaire["item"]))


def read_manifest(folder: Path) -> dict[str, Any] | None:
    """A run folder's manifest.json; None if it has none."""
    path = folder / "manifest.json"
    if not path.is_file():
        return None
    try:
        manifest = json.loads(path.read_text(encoding="utf-8"))
    except (json.JSONDecodeError, UnicodeDecodeError) as err:
        raise AnalysisInputError(f"{path}: not the manifest study run writes ({err})") from None
    if not isinstance(manifest, dict):
        raise AnalysisInputError(f"{path}: not the manifest study run writes (not an object)")
    return manifest

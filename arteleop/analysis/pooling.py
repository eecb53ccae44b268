"""Whether run folders may be pooled as cohorts of one design: no cohort counted twice (a run
repeated with its seed, a folder and its copy), and one design (the study files alike but for
the seed and the cohort's size), unless a comparison of designs is asked for."""

from __future__ import annotations

import itertools
import json
import tomllib
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import pandas as pd

from arteleop.analysis.data import StudyData, read_manifest
from arteleop.analysis.errors import AnalysisInputError

NOT_DESIGN = ("name", "seed", "cohort.size", "participants")
"""Study-file keys that may differ between cohorts of one design: the report's name, the seed
(another cohort), and who or how many take part (simulated: ``[cohort] size``; listed:
``[[participants]]``)."""

DIFFERENT = "Different designs, compared deliberately"
"""How a note on designs that differ begins."""

_ROW = ["modality", "round_trip_ms", "jitter_ms", "loss", "trial_index", "outcome",
        "completion_time_s", "placement_error_m"]  # fmt: skip
"""What makes a participant's trial rows theirs: a copy repeats all of them to the bit."""


def check_cohorts(
    folders: Sequence[Path], studies: Sequence[StudyData], allow_different_designs: bool = False
) -> list[str]:
    """Raise :class:`AnalysisInputError` if two of ``studies`` (read from ``folders``) are one
    cohort, or if their designs differ and ``allow_different_designs`` is not given; else the
    notes the report should carry (designs that differ, or that could not be checked)."""
    for (a, sa), (b, sb) in itertools.combinations(zip(folders, studies, strict=True), 2):
        _check_not_repeated(a, b)
        _check_not_copied(a, sa, b, sb)
    notes = []
    designs = {folder: _design(folder) for folder in folders}
    unknown = [str(f) for f, design in designs.items() if design is None]
    if unknown:
        notes.append(f"Designs not checked: no study.toml in {', '.join(unknown)}.")
    known = [(f, d) for f, d in designs.items() if d is not None]
    for folder, design in known[1:]:
        first, reference = known[0]
        differing = _differences(reference, design)
        if not differing:
            continue
        said = "; ".join(f"{key} ({_shown(reference.get(key))} in {first}, "
                         f"{_shown(design.get(key))} here)" for key in differing)  # fmt: skip
        if not allow_different_designs:
            raise AnalysisInputError(
                f"{folder / 'study.toml'}: not the design of {first}: {said}. Cohorts pooled "
                "must differ only in seed and size; give --allow-different-designs to compare "
                "the designs deliberately"
            )
        notes.append(f"{DIFFERENT}: {folder} differs from {first} in {said}.")
    return notes


def changed_constants_notes(folders: Sequence[Path]) -> list[str]:
    """What a report on ``folders`` says where their studies changed the simulated
    participant's constants (a study.toml's ``[operator_params]``): a sensitivity run, not the
    model. One note for the folders that changed the same ones; none for the model's own."""
    changed: dict[str, list[str]] = {}
    for folder in folders:
        path = folder / "study.toml"
        if not path.is_file():
            continue
        try:
            table = tomllib.loads(path.read_text(encoding="utf-8")).get("operator_params")
        except (tomllib.TOMLDecodeError, UnicodeDecodeError) as err:
            raise AnalysisInputError(f"{path}: not a study file ({err})") from None
        if table:
            said = ", ".join(f"{k} = {v}" for k, v in table.items())
            changed.setdefault(said, []).append(str(folder))
    return [f"A sensitivity run: the simulated participants of {', '.join(names)} have constants "
            f"changed from the model's ({said}; study.toml's [operator_params])."
            for said, names in changed.items()]  # fmt: skip


def _check_not_repeated(a: Path, b: Path) -> None:
    ma, mb = read_manifest(a), read_manifest(b)
    if ma is None or mb is None or "real" in (ma.get("cohort"), mb.get("cohort")):
        return  # people served one plan twice are two cohorts; their rows tell a copy
    keys = ("seed", "plan_sha256")
    if all(ma.get(k) is not None and ma.get(k) == mb.get(k) for k in keys):
        raise AnalysisInputError(
            f"{a} and {b} are one cohort run twice (seed {ma['seed']}, the same plan): the same "
            "simulated participants would count twice. Pool runs of other seeds (arteleop "
            "study run FILE --seed N)"
        )


def _check_not_copied(a: Path, sa: StudyData, b: Path, sb: StudyData) -> None:
    people_a, people_b = _people(sa.trials), _people(sb.trials)
    same = sorted(f"{pa} as {pb}" if pa != pb else pa
                  for pa, rows in people_a.items() for pb, other in people_b.items()
                  if rows == other)  # fmt: skip
    if same:
        raise AnalysisInputError(
            f"{b} repeats {a}'s trials row for row for {len(same)} participant(s) "
            f"({', '.join(same[:3])}{', ...' if len(same) > 3 else ''}): a copy of the folder, "
            "or one run twice. Each participant may count once: leave one of them out"
        )


def _people(trials: pd.DataFrame) -> dict[str, tuple]:
    """Each participant with a success: their experimental trials' rows, in order."""
    exp = trials[trials["phase"] == "experimental"].sort_values("trial_index")
    return {
        str(p): tuple(map(tuple, rows[_ROW].astype(str).to_numpy()))
        for p, rows in exp.groupby("participant")
        if (rows["outcome"] == "success").any()
    }


def _design(folder: Path) -> dict[str, Any] | None:
    path = folder / "study.toml"
    if not path.is_file():
        return None
    try:
        raw = tomllib.loads(path.read_text(encoding="utf-8"))
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as err:
        raise AnalysisInputError(f"{path}: not a study file ({err})") from None
    return {k: v for k, v in _flat(raw).items() if k not in NOT_DESIGN}


def _flat(table: dict[str, Any], prefix: str = "") -> dict[str, Any]:
    out: dict[str, Any] = {}
    for key, value in table.items():
        if isinstance(value, dict):
            out |= _flat(value, f"{prefix}{key}.")
        else:
            out[f"{prefix}{key}"] = value
    return out


def _differences(a: dict[str, Any], b: dict[str, Any]) -> list[str]:
    return sorted(k for k in a.keys() | b.keys() if a.get(k) != b.get(k))


def _shown(value: Any) -> str:
    text = "missing" if value is None else json.dumps(value)
    return text if len(text) <= 40 else text[:37] + "..."

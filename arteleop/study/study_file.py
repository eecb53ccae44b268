"""Study definitions as TOML files, read strictly (:mod:`.study_writing` writes them).

Every key is a field of the dataclasses in :mod:`arteleop.study.definition`; an unknown key, a
value of the wrong type or out of range is refused with the file, the line and the key.
"""

from __future__ import annotations

import dataclasses
import re
import tomllib
from pathlib import Path
from typing import Any, get_type_hints

from arteleop.errors import ConfigurationError, FrameGraphError, StudyDefinitionError
from arteleop.operator.simulated.params import OperatorParams
from arteleop.operator.simulated.traits import TraitDistribution
from arteleop.study.definition import (
    CohortConfig,
    ConditionSpec,
    FamiliarizationConfig,
    ParticipantSpec,
    StudyConfig,
)
from arteleop.study.pointing_design import PointingDesign
from arteleop.study.questionnaire_items import QuestionnaireItem
from arteleop.study.study_constants import refuse_unknown_constants
from arteleop.teleop.hand_filter import HandFilterConfig

TABLES: dict[str, type] = {
    "familiarization": FamiliarizationConfig,
    "cohort": CohortConfig,
    "operator": TraitDistribution,
    "operator_params": OperatorParams,
    "hand_filter": HandFilterConfig,
    "pointing": PointingDesign,
}
"""The study file's tables and what each is read into."""
QUESTIONNAIRE_FILE_KEY = "questionnaire_file"
"""Not a field: a TOML file of ``[[questionnaire]]`` tables, read into ``questionnaire``."""
CAMERA_GRAPH_KEY = "camera_graph"
"""Not a field: a graph file whose camera edge becomes ``camera_pose``."""
TEXT_FILE_KEYS = {"consent_file": "consent", "instructions_file": "instructions"}
"""Study-file keys read into a page's text: its Markdown from a file beside the study file (the
run folder's study.toml then holds the text itself, as shown)."""


def load_study_file(path: Path) -> tuple[StudyConfig, str]:
    """The definition in ``path`` and the file's text; refuses a start or target that the
    site would refuse (off the table, out of the arm's reach), naming the key's line."""
    path = Path(path)
    text = _read_text(
        path, f"{path}", f"no such study file. 'arteleop study init {path}' writes the default "
        "one to edit."
    )  # fmt: skip
    study = parse_study(text, str(path))
    _check_points(study, text, str(path))
    return study, text


def _check_points(study: StudyConfig, text: str, source: str) -> None:
    from arteleop.study.sites import StudySite  # loads the robot's model

    problem = StudySite().problem(study.start_xy_m, study.target_xy_m)
    if problem is not None:
        # Every problem names the point to move as Workspace.start_xy_m or .target_xy_m.
        key = "target_xy_m" if "Workspace.target_xy_m" in problem else "start_xy_m"
        raise StudyDefinitionError(f"{_Locator(text, source).at('', key)}: {key}: {problem}")


def parse_study(text: str, source: str = "<study>") -> StudyConfig:
    """A definition from TOML text; ``source`` names it in errors."""
    text = text.removeprefix("\ufeff")  # a byte-order mark some editors write first
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise StudyDefinitionError(f"{source}: not valid TOML: {err}.") from err
    if not data:
        raise StudyDefinitionError(
            f"{source} defines nothing (no key). 'arteleop study run' without a file runs the "
            "built-in default study; 'arteleop study init FILE' writes it to edit."
        )
    where = _Locator(text, source)
    top: dict[str, Any] = {}
    for key, value in data.items():
        if key in TABLES:
            if key == "operator_params" and isinstance(value, dict):
                refuse_unknown_constants(value, lambda k: where.at("operator_params", k))
            top[key] = _build(TABLES[key], value, key, where)
        elif key == "conditions":
            if not isinstance(value, list):
                raise StudyDefinitionError(
                    f"{where.at('', key)}: conditions must be [[conditions]] tables."
                )
            given = [k for k in ("modalities", "delay_ms") if k in data]
            if given:
                raise StudyDefinitionError(
                    f"{where.at('', given[0])}: {given[0]} and [[conditions]]: the conditions "
                    "give each trial's cues and network; remove one or the other."
                )
            if not value:
                raise StudyDefinitionError(
                    f"{where.at('', key)}: conditions = [] gives no condition; give "
                    "[[conditions]] tables (each a cue set over a network profile), or remove "
                    "the key to compare the modalities."
                )
            for index, item in enumerate(value):
                if item == {}:
                    raise StudyDefinitionError(
                        f"{where.at('conditions', '', index)}: an empty [[conditions]] table; "
                        "give its cues (cues = [] for no AR) and, for a delay, round_trip_ms."
                    )
            top[key] = tuple(
                _build(ConditionSpec, item, "conditions", where, index)
                for index, item in enumerate(value)
            )
        elif key == "participants":
            if not isinstance(value, list):
                raise StudyDefinitionError(
                    f"{where.at('', key)}: participants must be [[participants]] tables."
                )
            top[key] = tuple(
                _build(ParticipantSpec, item, "participants", where, index)
                for index, item in enumerate(value)
            )
            ids = [p.id for p in top[key]]
            for index, pid in enumerate(ids):
                if pid in ids[:index]:
                    raise StudyDefinitionError(
                        f"{where.at('participants', 'id', index)}: participant id {pid!r} is "
                        "used twice; each participant needs an id of their own."
                    )
        elif key == "questionnaire":
            top[key] = _items(value, where)
        elif key == QUESTIONNAIRE_FILE_KEY:
            if "questionnaire" in data:
                raise StudyDefinitionError(
                    f"{where.at('', key)}: {key} and [[questionnaire]]: give the items once, in "
                    "the study file or in a file."
                )
            top["questionnaire"] = _items_file(value, source, where.at("", key))
        elif key in TEXT_FILE_KEYS:
            field_name = TEXT_FILE_KEYS[key]
            if field_name in data:
                raise StudyDefinitionError(
                    f"{where.at('', key)}: {key} and {field_name}: give the page's text once, "
                    "in the study file or in a file."
                )
            top[field_name] = _text_file(key, value, source, where.at("", key))
        elif key == CAMERA_GRAPH_KEY:
            others = [k for k in ("camera_pose", "camera_offset_mm", "camera_offset_deg")
                      if k in data]  # fmt: skip
            if others:
                raise StudyDefinitionError(
                    f"{where.at('', key)}: camera_graph and {' and '.join(others)}: the graph's "
                    "pose replaces them; give one or the other."
                )
            top["camera_pose"] = _graph_camera_pose(value, source, where.at("", key))
        else:
            top[key] = value
    return _build(StudyConfig, top, "", where)


def _read_text(path: Path, named: str, missing: str) -> str:
    """``path``'s UTF-8 text; its absence or unreadability a message that begins ``named``."""
    try:
        return path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise StudyDefinitionError(f"{named}: {missing}") from None
    except (OSError, UnicodeDecodeError) as err:
        raise StudyDefinitionError(f"{named}: cannot read it ({err}).") from None


def _named_file(key: str, value: Any, source: str, at: str, missing: str) -> tuple[Path, str]:
    """The path and text of the file the study file's ``key`` names (relative to the study
    file); ``missing`` says what to put there if it is not."""
    if not isinstance(value, str) or not value:
        raise StudyDefinitionError(f"{at}: {key} must be a file name, got {value!r}.")
    path = Path(source).parent / value
    return path, _read_text(path, f"{at}: {key}: {path}", missing)


def _text_file(key: str, value: Any, source: str, at: str) -> str:
    """A page's Markdown, from the file the study file's ``key`` names."""
    path, text = _named_file(
        key, value, source, at, "no such file. Put the page's text (Markdown) there, the text "
        "your ethics board approved, or name its file relative to the study file."
    )  # fmt: skip
    if not text.strip():
        raise StudyDefinitionError(f"{at}: {key}: {path} is empty.")
    return text


def _items(value: Any, where: _Locator) -> tuple[QuestionnaireItem, ...]:
    """The questionnaire's items from its ``[[questionnaire]]`` tables."""
    if not isinstance(value, list):
        raise StudyDefinitionError(
            f"{where.at('', 'questionnaire')}: questionnaire must be [[questionnaire]] tables "
            "(id, text, low, high)."
        )
    if not value:
        raise StudyDefinitionError(
            f"{where.at('', 'questionnaire')}: questionnaire = [] asks nothing; give "
            "[[questionnaire]] tables, or remove the key for the original study's three items."
        )
    items = tuple(
        _build(QuestionnaireItem, item, "questionnaire", where, index)
        for index, item in enumerate(value)
    )
    ids = [item.id for item in items]
    for index, item_id in enumerate(ids):
        if item_id in ids[:index]:
            raise StudyDefinitionError(
                f"{where.at('questionnaire', 'id', index)}: questionnaire item id {item_id!r} is "
                "used twice; each item needs an id of its own."
            )
    return items


def _items_file(value: Any, source: str, at: str) -> tuple[QuestionnaireItem, ...]:
    """The items of the file the study file's ``questionnaire_file`` names: its
    ``[[questionnaire]]`` tables, each problem named by that file's line."""
    path, text = _named_file(
        QUESTIONNAIRE_FILE_KEY, value, source, at, "no such file. Put the items there as "
        "[[questionnaire]] tables (id, text, low, high), or name its file relative to the study "
        "file."
    )  # fmt: skip
    try:
        data = tomllib.loads(text.removeprefix("\ufeff"))
    except tomllib.TOMLDecodeError as err:
        raise StudyDefinitionError(f"{path}: not valid TOML: {err}.") from None
    where = _Locator(text, str(path))
    extra = [k for k in data if k != "questionnaire"]
    if extra or not data:
        raise StudyDefinitionError(
            f"{where.at('', extra[0]) if extra else path}: expected [[questionnaire]] tables "
            f"only (id, text, low, high){f', not {extra[0]!r}' if extra else ''}."
        )
    return _items(data["questionnaire"], where)


def _graph_camera_pose(value: Any, source: str, at: str) -> list[list[float]]:
    """The camera's pose in a transform graph file named by the ``camera_graph`` key."""
    from arteleop.frames import TransformGraph
    from arteleop.scene import BASE_FRAME, CAMERA_FRAME

    if not isinstance(value, str):
        raise StudyDefinitionError(f"{at}: camera_graph must be a file name, got {value!r}.")
    path = Path(source).parent / value
    try:
        T = TransformGraph.load(path).T(BASE_FRAME, CAMERA_FRAME)
    except FrameGraphError as err:
        raise StudyDefinitionError(
            f"{at}: camera_graph: {err}. 'arteleop calibrate --out {value}' writes such a file."
        ) from None
    return T.tolist()  # checked and made a tuple as camera_pose


def _build(cls: type, values: Any, table: str, where: _Locator, index: int | None = None) -> Any:
    if not isinstance(values, dict):
        raise StudyDefinitionError(f"{where.at('', table)}: [{table}] must be a table.")
    hints = get_type_hints(cls)
    names = [f.name for f in dataclasses.fields(cls)]
    kwargs = {}
    for key, value in values.items():
        if key not in names:
            raise StudyDefinitionError(
                f"{where.at(table, key, index)}: unknown key {_dotted(table, key)!r}. Valid "
                f"keys{' in [' + table + ']' if table else ''}: {', '.join(names)}."
            )
        kwargs[key] = _convert(value, hints[key], where.at(table, key, index), table, key)
    required = [f.name for f in dataclasses.fields(cls) if f.default is dataclasses.MISSING
                and f.default_factory is dataclasses.MISSING]  # fmt: skip
    missing = [name for name in required if name not in kwargs]
    if missing:
        raise StudyDefinitionError(
            f"{where.at(table, '', index)}: [{'[' + table + ']' if index is not None else table}]"
            f" has no {missing[0]!r}; give {', '.join(required)}."
        )
    try:
        return cls(**kwargs)
    except ConfigurationError as err:
        # The model's own classes name themselves; the file names the table.
        message = str(err).replace(f"{cls.__name__}.", f"{table}.")
        key = _key_in(message, names)
        raise StudyDefinitionError(f"{where.at(table, key or '', index)}: {message}") from None


def _convert(value: Any, hint: Any, at: str, table: str, key: str) -> Any:
    """Checks a TOML value against the field's type; lists become tuples."""
    hint_text = str(hint)
    name = _dotted(table, key)
    if dataclasses.is_dataclass(value) or (
        isinstance(value, tuple) and value and dataclasses.is_dataclass(value[0])
    ):
        return value  # a nested table, already built
    if hint_text.startswith("tuple[tuple"):
        expected = float if "float" in hint_text else str
        if not (
            isinstance(value, list)
            and all(isinstance(v, list) and all(_is(x, expected) for x in v) for v in value)
        ):
            kind = "numbers" if expected is float else "text"
            raise StudyDefinitionError(
                f"{at}: {name} must be a list of lists of {kind}, got {value!r}."
            )
        return tuple(tuple(expected(x) for x in v) for v in value)
    if hint_text.startswith("tuple"):
        if not isinstance(value, list):
            raise StudyDefinitionError(f"{at}: {name} must be a list, got {value!r}.")
        expected = str if "str" in hint_text else float
        if not all(_is(v, expected) for v in value):
            kind = "text" if expected is str else "numbers"
            raise StudyDefinitionError(f"{at}: {name} must be a list of {kind}, got {value!r}.")
        size = hint_text.count("float")
        if size in (2, 3) and len(value) != size:
            what = "two numbers (x, y)" if size == 2 else "three numbers (x, y, z)"
            raise StudyDefinitionError(f"{at}: {name} must be {what}, got {value!r}.")
        return tuple(float(v) if expected is float else v for v in value)
    for kind, label in ((bool, "true or false"), (int, "a whole number"), (str, "text")):
        if hint is kind and not _is(value, kind):
            raise StudyDefinitionError(f"{at}: {name} must be {label}, got {value!r}.")
    if hint is float:
        if not _is(value, float):
            raise StudyDefinitionError(f"{at}: {name} must be a number, got {value!r}.")
        return float(value)
    return value


def _is(value: Any, kind: type) -> bool:
    if kind is float:
        return isinstance(value, int | float) and not isinstance(value, bool)
    if kind is int:
        return isinstance(value, int) and not isinstance(value, bool)
    return isinstance(value, kind)


def _dotted(table: str, key: str) -> str:
    return f"{table}.{key}" if table else key


def _key_in(message: str, names: list[str]) -> str | None:
    """The field a definition error is about: its message names it first."""
    found = re.search(r"(?:^|[ .:])(\w+) = ", message)
    if found and found.group(1) in names:
        return found.group(1)
    return next((n for n in names if re.search(rf"\b{n}\b", message)), None)


class _Locator:
    """Finds the line of a key in the file's text."""

    def __init__(self, text: str, source: str) -> None:
        self.lines = text.splitlines()
        self.source = source

    def at(self, table: str, key: str, index: int | None = None) -> str:
        line = self._line(table, key, index)
        return f"{self.source} line {line}" if line else self.source

    def _line(self, table: str, key: str, index: int | None) -> int | None:
        section, seen = "", -1
        for number, raw in enumerate(self.lines, start=1):
            stripped = raw.split("#", 1)[0].strip()
            header = re.fullmatch(r"\[\[?\s*([\w.]+)\s*\]\]?", stripped)
            if header:
                section = header.group(1)
                if section == table and stripped.startswith("[["):
                    seen += 1
                if section == table and not key and (index is None or seen == index):
                    return number
                continue
            if section != table or (index is not None and seen != index):
                continue
            if key and re.match(rf"{re.escape(key)}\s*=", stripped):
                return number
        return None


def first_difference(a: StudyConfig, b: StudyConfig) -> str | None:
    """The dotted key of the first field in which two definitions differ, or None."""
    for f in dataclasses.fields(a):
        x, y = getattr(a, f.name), getattr(b, f.name)
        if dataclasses.is_dataclass(x) and dataclasses.is_dataclass(y):
            for g in dataclasses.fields(x):  # type: ignore[arg-type]
                if getattr(x, g.name) != getattr(y, g.name):
                    return f"{f.name}.{g.name}"
        elif x != y:
            return f.name
    return None

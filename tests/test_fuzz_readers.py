"""Property-based tests of the readers of what users hand arteleop: study files, wearable
recordings, trials tables. The contract: a clean result, or one of the project's errors (whose
message names the file); never another exception, never a hang.

The default profile keeps the suite's time; ``HYPOTHESIS_PROFILE=fuzz`` runs many more cases.
"""

from __future__ import annotations

import json
import os
import string
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from arteleop.analysis import AnalysisInputError, load_study
from arteleop.analysis.data import TRIAL_COLUMNS
from arteleop.errors import ArteleopError
from arteleop.operator import COLUMNS, load_recording
from arteleop.study import parse_study, study_text
from arteleop.study.definition import StudyConfig

settings.register_profile("default", max_examples=60, deadline=2000,
                          suppress_health_check=[HealthCheck.function_scoped_fixture])  # fmt: skip
settings.register_profile("fuzz", max_examples=3000, deadline=5000,
                          suppress_health_check=[HealthCheck.function_scoped_fixture])  # fmt: skip
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "default"))

DEFAULT_LINES = study_text(StudyConfig()).splitlines()

toml_scalars = st.one_of(
    st.integers(-(10**25), 10**25).map(str), st.floats(allow_nan=True).map(repr),
    st.text(string.printable, max_size=8).map(json.dumps), st.sampled_from(["true", "[]", "{}",
    "[1, 2]", '["none", "full"]', "[[0.1]]", "inf", "nan", "-0.0", "1e309"]),
)  # fmt: skip


@st.composite
def study_texts(draw: st.DrawFn) -> str:
    """The default definition with some of its lines' values replaced, lines dropped or
    duplicated, and now and then noise: mostly near-valid files, the hardest to read right."""
    lines = list(DEFAULT_LINES)
    for _ in range(draw(st.integers(0, 6))):
        k = draw(st.integers(0, len(lines) - 1))
        action = draw(st.sampled_from(["value", "drop", "copy", "noise"]))
        if action == "value" and "=" in lines[k]:
            lines[k] = lines[k].split("=", 1)[0] + "= " + draw(toml_scalars)
        elif action == "drop":
            lines.pop(k)
        elif action == "copy":
            lines.insert(k, lines[k])
        else:
            lines.insert(k, draw(st.text(string.printable, max_size=30)))
    return "\n".join(lines) + "\n"


@given(study_texts())
def test_the_study_file_reader_gives_a_definition_or_its_error(text: str) -> None:
    try:
        study = parse_study(text, "fuzz.toml")
    except ArteleopError as err:
        assert str(err).startswith("fuzz.toml")
    else:  # what was read is written out and read back the same
        assert parse_study(study_text(study), "again.toml") == study


cells = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True).map(repr), st.integers(-5, 5).map(str),
    st.sampled_from(["", "1.0", "0.5", "nan", "inf", "x", "1,2", '"', "\\n"]),
)  # fmt: skip


@given(
    rows=st.lists(st.lists(cells, min_size=12, max_size=15), max_size=40),
    header=st.sampled_from([",".join(COLUMNS), ",".join(COLUMNS[:-1]), "time_s,grip", ""]),
    rate=st.one_of(st.sampled_from([100, 0, -1, 1e6, "x", None]), st.floats()),
    shape=st.sampled_from(["object", "list", "number", "no arm", "arm list"]),
)
@settings(deadline=None)
def test_the_recording_loader_gives_a_recording_or_its_error(
    tmp_path_factory: pytest.TempPathFactory, rows, header: str, rate, shape: str
) -> None:
    folder = tmp_path_factory.mktemp("rec")
    csv = folder / "r.csv"
    csv.write_text(header + "\n" + "\n".join(",".join(r) for r in rows) + "\n")
    sidecar = {"format": "arteleop-wearable-recording", "version": 2, "subject_id": "S",
               "rate_hz": rate, "arm": {}, "units": {},
               "calibration_posture": {"angles_rad": {}, "torso_heading_rad": 0.0,
                                       "hold_s": 1.0}}  # fmt: skip
    if shape == "no arm":
        del sidecar["arm"]
    elif shape == "arm list":
        sidecar["arm"] = [0.3, 0.25]
    data = {"object": sidecar, "list": [sidecar], "number": 3}.get(shape, sidecar)
    csv.with_suffix(".json").write_text(json.dumps(data))
    try:
        rec = load_recording(csv)
    except ArteleopError as err:
        assert str(csv) in str(err) or str(csv.with_suffix(".json")) in str(err)
    else:
        assert np.isfinite(rec.time_s).all() and np.isfinite(rec.sensor_quat_wxyz).all()


trial_cells = st.one_of(
    cells, st.sampled_from(["success", "timeout", "experimental", "familiarization", "none",
                            "full", "P01", "P02", "trajectories/P01/1.csv", "../x.csv"]),
)  # fmt: skip


@given(
    rows=st.lists(st.lists(trial_cells, min_size=len(TRIAL_COLUMNS), max_size=len(TRIAL_COLUMNS)),
                  max_size=30),
    columns=st.sampled_from([TRIAL_COLUMNS, TRIAL_COLUMNS[:9], (*TRIAL_COLUMNS[:5], "extra")]),
)  # fmt: skip
def test_the_trials_reader_gives_a_study_or_its_error(
    tmp_path_factory: pytest.TempPathFactory, rows, columns
) -> None:
    folder: Path = tmp_path_factory.mktemp("trials")
    lines = [",".join(columns)] + [",".join(r[: len(columns)]) for r in rows]
    (folder / "trials.csv").write_text("\n".join(lines) + "\n")
    try:
        study = load_study(folder)
    except AnalysisInputError as err:
        assert str(folder) in str(err)
    else:
        assert len(study.trials) == len(rows)
        numbers = study.trials.select_dtypes("number").to_numpy()
        assert not np.isinf(numbers).any()
        for name in study.trials["trajectory_file"]:
            assert not name or folder.resolve() in (folder / name).resolve().parents

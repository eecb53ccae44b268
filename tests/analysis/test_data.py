"""Bad study files: each error names the file, the line, the column and the value."""

from pathlib import Path

import pandas as pd
import pytest

from arteleop.analysis import AnalysisInputError, load_study
from tests.analysis.make_study import make_run


@pytest.fixture(scope="module")
def run(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return make_run(tmp_path_factory.mktemp("run"), trajectories=False)


def _broken(run: Path, tmp_path: Path, edit) -> Path:
    df = pd.read_csv(run / "trials.csv", dtype=str, keep_default_na=False)
    df = edit(df)
    df.to_csv(tmp_path / "trials.csv", index=False)
    return tmp_path / "trials.csv"


def test_run_folder_and_bare_trials_csv(run: Path) -> None:
    study = load_study(run)
    assert study.participants is not None and study.questionnaire is not None
    assert len(study.analysed_trials()) == 22 * 5 - 1
    bare = load_study(run / "trials.csv")
    assert bare.participants is None
    assert load_study(run / "trials.csv", run / "participants.csv").participants is not None


def test_unknown_modality(run: Path, tmp_path: Path) -> None:
    path = _broken(
        run, tmp_path, lambda d: d.assign(modality=d["modality"].replace("full", "full_ar"))
    )
    with pytest.raises(
        AnalysisInputError,
        match=r"line \d+, column modality: unknown value 'full_ar'. Expected one of: none",
    ):
        load_study(path)


def test_misspelt_column_gets_a_suggestion(run: Path, tmp_path: Path) -> None:
    path = _broken(
        run,
        tmp_path,
        lambda d: d.rename(columns={"placement_error_m": "placement_eror_m"}),
    )
    with pytest.raises(
        AnalysisInputError,
        match=r"line 1: unknown column 'placement_eror_m'. Did you mean 'placement_error_m'\?",
    ):
        load_study(path)


def test_missing_required_column(run: Path, tmp_path: Path) -> None:
    path = _broken(run, tmp_path, lambda d: d.drop(columns=["outcome"]))
    with pytest.raises(AnalysisInputError, match=r"line 1: missing required column\(s\) outcome"):
        load_study(path)


def test_non_numeric_value(run: Path, tmp_path: Path) -> None:
    path = _broken(
        run,
        tmp_path,
        lambda d: d.assign(completion_time_s=d["completion_time_s"].where(d.index != 6, "12,5 s")),
    )
    with pytest.raises(
        AnalysisInputError, match=r"line 8, column completion_time_s: '12,5 s' is not a number"
    ):
        load_study(path)


def test_two_experimental_trials_in_one_modality(run: Path, tmp_path: Path) -> None:
    def dup(d: pd.DataFrame) -> pd.DataFrame:
        d.loc[4, "modality"] = d.loc[3, "modality"]  # P01's 2nd experimental trial copies the 1st
        return d

    path = _broken(run, tmp_path, dup)
    with pytest.raises(
        AnalysisInputError,
        match=r"lines 5, 6: participant 'P01' has 2 experimental trials in modality 'none'",
    ):
        load_study(path)


def test_questionnaire_score_out_of_range(run: Path, tmp_path: Path) -> None:
    for name in ("trials.csv", "participants.csv"):
        (tmp_path / name).write_bytes((run / name).read_bytes())
    q = pd.read_csv(run / "questionnaire.csv")
    q.loc[10, "score"] = 9
    q.to_csv(tmp_path / "questionnaire.csv", index=False)
    with pytest.raises(
        AnalysisInputError, match=r"questionnaire.csv, line 12, column score: 9; expected 1 to 7"
    ):
        load_study(tmp_path)


def test_missing_trials_file(tmp_path: Path) -> None:
    with pytest.raises(AnalysisInputError, match=r"trials.csv: no such file"):
        load_study(tmp_path)

"""A study's own questionnaire: its items from the study file or a file beside it, asked of
people, answered by simulated participants where the model can, analysed item by item."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import pandas as pd
import pytest

from arteleop.analysis import AnalysisInputError, analyse, load_study
from arteleop.errors import RunFolderError, StudyDefinitionError
from arteleop.study import (
    CohortConfig,
    load_study_file,
    parse_study,
    served_run,
    simulated_answers,
    study_text,
)
from arteleop.study.answers import merge_answers
from arteleop.study.demographics import Demographics
from arteleop.study.questionnaire_items import modelled_items

ITEMS = """\
[[questionnaire]]
id = "workload"
text = "The task asked a lot of me"
low = "very little"
high = "a great deal"

[[questionnaire]]
id = "ease"
text = "The task was easy to do"
"""


def test_a_questionnaire_file_beside_the_study_file_is_what_the_study_asks(tmp_path: Path) -> None:
    (tmp_path / "items.toml").write_text(ITEMS)
    (tmp_path / "study.toml").write_text('questionnaire_file = "items.toml"\n')
    study, _ = load_study_file(tmp_path / "study.toml")
    assert [(i.id, i.low, i.high) for i in study.questionnaire] == [
        ("workload", "very little", "a great deal"), ("ease", "not at all", "very much")
    ]  # fmt: skip
    # The run folder's study.toml holds the items themselves, as asked.
    assert parse_study(study_text(study)).questionnaire == study.questionnaire


@pytest.mark.parametrize(
    ("items", "message"),
    [
        (ITEMS.replace('"workload"', '"Work load"'),
         "items.toml line 2: questionnaire.id = 'Work load': expected lower-case letters, "
         "digits and _, a letter first, at most 32 (it names the item in questionnaire.csv)."),
        (ITEMS.replace('"workload"', '"ease"'),
         "items.toml line 8: questionnaire item id 'ease' is used twice; each item needs an id "
         "of its own."),
        ('[[questionnaire]]\nid = "ease"\n',
         "items.toml line 1: [[questionnaire]] has no 'text'; give id, text."),
        ('seed = 1\n', "items.toml line 1: expected [[questionnaire]] tables only (id, text, low, "
         "high), not 'seed'."),
        (ITEMS.replace('"very little"', '"very\\tlittle"'),
         "items.toml line 4: questionnaire.low = 'very\\tlittle' (item 'workload'): expected one "
         "line of printable text."),
    ],
)  # fmt: skip
def test_a_bad_item_is_refused_at_its_line_in_its_file(
    tmp_path: Path, items: str, message: str
) -> None:
    (tmp_path / "items.toml").write_text(items)
    (tmp_path / "study.toml").write_text('seed = 1\nquestionnaire_file = "items.toml"\n')
    with pytest.raises(StudyDefinitionError) as err:
        load_study_file(tmp_path / "study.toml")
    assert str(err.value) == f"{tmp_path / message}"


def test_people_answer_the_studys_items_and_merged_answers_are_checked_against_them(
    tmp_path: Path,
) -> None:
    study = parse_study(
        'modalities = ["none", "task", "full"]\n[familiarization]\ntrials = 0\n' + ITEMS
    )
    study = replace(study, cohort=CohortConfig(2, 0, 0, 0))
    with served_run(tmp_path / "run", study) as run:
        for person, score in (("P01", 2), ("P02", 6)):
            run.consent(person, Demographics(30, "female", "right", 4, 1, 4, 1))
            ratings = {(c, i.id): score for c in ("embodiment", "manipulation", "task")
                       for i in study.questionnaire}  # fmt: skip
            run.answer(person, ratings)
    answers = pd.read_csv(tmp_path / "run" / "questionnaire.csv")
    assert list(dict.fromkeys(answers["item"])) == ["workload", "ease"]
    # A lab's answers to its own item are merged against the study's items, not the original's.
    merged = tmp_path / "answers.csv"
    merged.write_text("participant,ar_class,item,score\nP01,task,workload,7\n")
    merge_answers(tmp_path / "run", merged)
    merged.write_text("participant,ar_class,item,score\nP01,task,presence,7\n")
    with pytest.raises(RunFolderError, match="item 'presence'; expected one of the study's "
                       "workload, ease"):  # fmt: skip
        merge_answers(tmp_path / "run", merged)


def test_simulated_participants_answer_only_the_items_the_model_has() -> None:
    asked = parse_study(ITEMS + '[[questionnaire]]\nid = "presence"\ntext = "I was there"\n')
    # Of the three items, only "ease" is the original's as the original asked it.
    assert modelled_items(asked) == ["ease"]
    trials = pd.DataFrame({
        "modality": ["none", "task"], "outcome": ["success", "success"],
        "completion_time_s": [30.0, 20.0], "placement_error_m": [0.02, 0.01],
    })  # fmt: skip
    every = simulated_answers("P01", (0, 4, 0), trials, 120.0)
    asked = simulated_answers("P01", (0, 4, 0), trials, 120.0, items=("workload", "ease"))
    assert asked == [row for row in every if row[2] == "ease"] and len(asked) == 3


def test_the_analysis_compares_the_classes_on_each_item_it_finds(tmp_path: Path) -> None:
    from tests.analysis.make_study import make_run

    run = make_run(tmp_path / "study", trajectories=False)
    q = pd.read_csv(run / "questionnaire.csv")
    q = q[q["item"] == "ease"].assign(item="workload")
    q.to_csv(run / "questionnaire.csv", index=False)
    tests = analyse(load_study(run)).tests
    measures = {m for m in tests["measure"] if m.startswith("questionnaire:")}
    assert measures == {"questionnaire:workload"}
    q.assign(item="Work load").to_csv(run / "questionnaire.csv", index=False)
    with pytest.raises(AnalysisInputError, match="column item: 'Work load' is not an item id"):
        load_study(run)


def test_a_run_says_which_items_its_simulated_participants_leave_unanswered(
    tmp_path: Path,
) -> None:
    from arteleop.study import run_study

    study = parse_study(
        'modalities = ["task"]\ntimeout_s = 2.0\n[familiarization]\ntrials = 0\n'
        "[cohort]\nsize = 1\navr_experts = 0\ngames_experts = 0\nboth_experts = 0\n" + ITEMS
    )
    run = run_study(study, tmp_path / "run", workers=1)
    assert run.notes == (
        "questionnaire.csv: the simulated participants answer no workload: they answer only the "
        "original study's items, in its words (docs/guides/serving-a-study.md); 'arteleop study "
        "answer' adds real answers.",
    )
    answers = pd.read_csv(tmp_path / "run" / "questionnaire.csv")
    assert set(answers["item"]) == {"ease"}

"""The questionnaire asks about the AR classes a study draws, of people and of simulated
participants alike."""

from pathlib import Path

import pandas as pd

from arteleop.study import (
    CohortConfig,
    FamiliarizationConfig,
    StudyConfig,
    classes_shown,
    served_run,
    simulated_answers,
)
from arteleop.study.definition import ConditionSpec

PEOPLE = CohortConfig(size=2, avr_experts=0, games_experts=0, both_experts=0)


def _study(**kwargs: object) -> StudyConfig:
    return StudyConfig(cohort=PEOPLE, familiarization=FamiliarizationConfig(trials=0), **kwargs)


def test_the_classes_asked_about_are_those_a_condition_draws() -> None:
    assert classes_shown(StudyConfig()) == ("embodiment", "manipulation", "task")
    assert classes_shown(_study(modalities=("none", "manipulation"))) == ("manipulation",)
    assert classes_shown(_study(modalities=("none", "full"))) == (
        "embodiment", "manipulation", "task",
    )  # fmt: skip
    # A layer of a class is enough: the beam alone is one of the manipulation aids.
    crossed = _study(conditions=(ConditionSpec(("beam",)), ConditionSpec(("ghost", "task"))))
    assert classes_shown(crossed) == ("embodiment", "manipulation", "task")
    # Practice aids are not compared; the predictive ghost is none of the three classes.
    practice = FamiliarizationConfig(trials=1, modality="full")
    alone = StudyConfig(cohort=PEOPLE, familiarization=practice,
                        modalities=("none", "predictive"))  # fmt: skip
    assert classes_shown(alone) == ()


def test_a_simulated_participant_answers_the_same_of_a_class_whatever_else_is_asked() -> None:
    trials = pd.DataFrame({
        "modality": ["none", "task"], "outcome": ["success", "success"],
        "completion_time_s": [30.0, 20.0], "placement_error_m": [0.02, 0.01],
    })  # fmt: skip
    every = simulated_answers("P01", (0, 4, 0), trials, 120.0)
    asked = simulated_answers("P01", (0, 4, 0), trials, 120.0, ("task",))
    assert len(every) == 9 and asked == [row for row in every if row[1] == "task"]


def test_with_no_class_drawn_nobody_is_asked(tmp_path: Path) -> None:
    with served_run(tmp_path / "run", _study(modalities=("none", "predictive"))) as run:
        assert run.answered("P01") and run.answered("P02")
        assert run.current() is not None and run.current().id == "P01"  # trials still due

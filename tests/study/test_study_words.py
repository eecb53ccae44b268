"""What the served pages say of the study: only what is true of its study file."""

from __future__ import annotations

from arteleop.ar_features.session_pages import EXPERIENCE, HOURS, _rated, _scale
from arteleop.study import FamiliarizationConfig, StudyConfig
from arteleop.study.session_words import (
    CONSENT,
    DRIVE,
    POINTING_TUTORIAL,
    PRACTICE_FIRST,
    TUTORIAL,
    consent_text,
    instructions_text,
)


def _what_you_do(text: str) -> str:
    return text.split("**What you do.** ")[1].split("\n\n")[0].replace("\n", " ")


def test_the_built_in_consent_says_the_studys_own_trials_and_limit() -> None:
    # It said "with the mouse", "a few practice trials" and "about half an hour" whatever the
    # study was.
    assert _what_you_do(consent_text(StudyConfig())) == (
        "With the mouse or the keyboard you move the gripper of a robot arm, pick up a bowl and "
        "put it on a target: 3 practice trials and then 5 measured trials, one under each of 5 "
        "different display conditions. Each trial ends when the bowl stands still after you let "
        "it go, or after 2 minutes at most. Afterwards you rate the displays."
    )
    short = StudyConfig(modalities=("none",), timeout_s=90.0,
                        familiarization=FamiliarizationConfig(trials=0))  # fmt: skip
    assert "on a target: 1 measured trial. Each trial ends" in _what_you_do(consent_text(short))
    assert "or after 90 seconds at most." in _what_you_do(consent_text(short))
    assert "half an hour" not in CONSENT and "a few practice" not in CONSENT


def test_the_built_in_consent_of_a_pointing_study_says_its_task_and_blocks() -> None:
    from arteleop.study.study_file import parse_study

    one_lag = parse_study(
        'task = "pointing"\n[pointing]\nrepetitions = 2\ntimeout_s = 30\n'
        "[[conditions]]\ncues = []\nround_trip_ms = 0\n"
    )
    text = consent_text(one_lag)
    assert _what_you_do(text) == (
        "With the mouse or the keyboard you move the gripper of a robot arm over a cross on a "
        "table, then over a circle, and close its grip there: 18 measured trials. Each trial ends "
        "when you close the grip, or after 30 seconds at most."
    )
    assert "a delay in a robot's camera view" in text and "ratings" not in text
    assert instructions_text(one_lag) == DRIVE + POINTING_TUTORIAL


def test_a_study_files_own_consent_is_shown_as_it_is() -> None:
    own = "Approved by the ethics board, ref. 2026/17.\n\nYou will **pick up a bowl**."
    assert consent_text(StudyConfig(consent=own)) == own


def test_every_rating_scale_names_its_ends_and_answers_a_number() -> None:
    items = StudyConfig().questionnaire
    for ends in (EXPERIENCE, *((item.low, item.high) for item in items)):
        options = _scale(ends)
        assert options[0] == f"1 ({ends[0]})" and options[-1] == f"7 ({ends[1]})"
        assert [_rated(o) for o in options] == [1, 2, 3, 4, 5, 6, 7]
    assert _rated("(choose)") == 0 and _rated("") == 0
    assert HOURS[0] == "under 2 h"  # the original's "under 1 h" left 1-2 h without an answer


def test_a_consent_file_beside_the_study_file_is_the_page_and_the_runs_record(tmp_path) -> None:
    from arteleop.study import load_study_file, study_text
    from arteleop.study.study_file import parse_study

    (tmp_path / "consent.md").write_text("Approved text, ref. 2026/17.\n", encoding="utf-8")
    (tmp_path / "study.toml").write_text('consent_file = "consent.md"\n')
    study, _ = load_study_file(tmp_path / "study.toml")
    assert consent_text(study) == "Approved text, ref. 2026/17.\n"
    # The run folder's study.toml holds the text as shown, not the file's name.
    assert parse_study(study_text(study)).consent == "Approved text, ref. 2026/17.\n"


def test_a_consent_file_that_cannot_be_the_page_is_refused(tmp_path) -> None:
    import pytest

    from arteleop.errors import StudyDefinitionError
    from arteleop.study import load_study_file

    cases = {
        'consent_file = "missing.md"\n': f"{tmp_path / 'study.toml'} line 1: consent_file: "
        f"{tmp_path / 'missing.md'}: no such file. Put the page's text (Markdown) there, the "
        "text your ethics board approved, or name its file relative to the study file.",
        'consent = "x"\nconsent_file = "c.md"\n': f"{tmp_path / 'study.toml'} line 2: "
        "consent_file and consent: give the page's text once, in the study file or in a file.",
        'consent_file = "empty.md"\n': f"{tmp_path / 'study.toml'} line 1: consent_file: "
        f"{tmp_path / 'empty.md'} is empty.",
    }
    (tmp_path / "empty.md").write_text("\n")
    for text, message in cases.items():
        (tmp_path / "study.toml").write_text(text)
        with pytest.raises(StudyDefinitionError) as err:
            load_study_file(tmp_path / "study.toml")
        assert str(err.value) == message


def test_the_instructions_are_the_study_files_own_or_say_practice_comes_first_only_if_it_does(
    tmp_path,
) -> None:
    from dataclasses import replace

    from arteleop.study import FamiliarizationConfig, load_study_file, study_text
    from arteleop.study.study_file import parse_study

    assert instructions_text(StudyConfig()) == DRIVE + TUTORIAL + "\n" + PRACTICE_FIRST
    none = replace(StudyConfig(), familiarization=FamiliarizationConfig(trials=0))
    assert instructions_text(none) == DRIVE + TUTORIAL and "practice" not in TUTORIAL
    (tmp_path / "drive.md").write_text("Use the joystick.\n", encoding="utf-8")
    (tmp_path / "study.toml").write_text('instructions_file = "drive.md"\n')
    study, _ = load_study_file(tmp_path / "study.toml")
    assert instructions_text(study) == "Use the joystick.\n"
    assert parse_study(study_text(study)).instructions == "Use the joystick.\n"
    (tmp_path / "study.toml").write_text('instructions = "x"\ninstructions_file = "drive.md"\n')
    import pytest

    from arteleop.errors import StudyDefinitionError

    with pytest.raises(StudyDefinitionError, match="line 2: instructions_file and instructions"):
        load_study_file(tmp_path / "study.toml")

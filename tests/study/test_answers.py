"""Real questionnaire answers replace a participant's simulated ones; bad rows change nothing."""

from __future__ import annotations

from pathlib import Path

import pytest

from arteleop.cli import main
from arteleop.errors import RunFolderError
from arteleop.study import RunFolder
from arteleop.study.answers import merge_answers

HEADER = "participant,ar_class,item,score\n"


def _run(tmp_path: Path) -> Path:
    folder = RunFolder(tmp_path / "run")
    folder.start("seed = 0\n", {"format_version": 1}, "participant\nP01\nP02\n")
    simulated = "".join(
        f"{p},{c},{i},4\n"
        for p in ("P01", "P02")
        for c in ("embodiment", "manipulation", "task")
        for i in ("presence", "embodiment", "ease")
    )
    folder.write_questionnaire(HEADER + simulated)
    return folder.path


def test_answers_replace_those_participants_rows_in_order(tmp_path: Path, capsys) -> None:
    run = _run(tmp_path)
    answers = tmp_path / "answers.csv"
    answers.write_text(HEADER + "P02,task,ease,7\nP02,embodiment,presence,1\n")
    assert main(["study", "answer", str(run), str(answers)]) == 0
    assert "merged answers of 1 participants" in capsys.readouterr().out
    lines = (run / "questionnaire.csv").read_text().splitlines()
    assert lines[0] == HEADER.strip()
    assert len(lines) == 1 + 9 + 2  # P01's nine simulated answers, P02's two real ones
    assert lines[-2:] == ["P02,embodiment,presence,1", "P02,task,ease,7"]
    assert all(line.endswith(",4") for line in lines[1:10])


@pytest.mark.parametrize(
    ("row", "message"),
    [
        ("P09,task,ease,7", "line 3: participant 'P09' is not in participants.csv"),
        ("P01,tasks,ease,7", "line 3: ar_class 'tasks'; expected one of embodiment, "
                             "manipulation, task"),
        ("P01,task,joy,7", "line 3: item 'joy'; expected one of the study's presence, "
                            "embodiment, ease"),
        ("P01,task,ease,8", "line 3: score '8'; expected a whole number 1-7"),
    ],
)  # fmt: skip
def test_a_bad_row_is_named_and_nothing_is_merged(tmp_path: Path, row: str, message: str) -> None:
    run = _run(tmp_path)
    before = (run / "questionnaire.csv").read_bytes()
    answers = tmp_path / "answers.csv"
    answers.write_text(HEADER + "P01,task,ease,6\n" + row + "\n")
    with pytest.raises(RunFolderError) as err:
        merge_answers(run, answers)
    assert str(err.value) == f"{answers} {message}. Nothing was merged."
    assert (run / "questionnaire.csv").read_bytes() == before


def test_a_file_with_the_wrong_header_is_refused(tmp_path: Path) -> None:
    run = _run(tmp_path)
    answers = tmp_path / "answers.csv"
    answers.write_text("who,class,item,score\nP01,task,ease,6\n")
    with pytest.raises(RunFolderError, match=r"line 1: header who,class,item,score; expected "
                       r"participant,ar_class,item,score"):  # fmt: skip
        merge_answers(run, answers)

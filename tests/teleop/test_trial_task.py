"""A study's task: named in the study file, done by the participant and scored by the site."""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
import pytest

from arteleop.errors import StudyDefinitionError
from arteleop.scene import SiteConfig
from arteleop.study import parse_study, run_study
from arteleop.teleop import PICK_AND_PLACE, TaskMonitor, TaskSite, trial_task
from tests.teleop.squeeze_task import ABOVE_M, SQUEEZE, SqueezeMonitor

WORKSPACE = SiteConfig().workspace
OWN = "tests.teleop.squeeze_task:SQUEEZE"
EXPECTED = (
    "expected 'pick-and-place', 'pointing', or a task of your own as 'package.module:NAME' "
    "(docs/guides/extending.md)."
)


def test_a_task_of_ones_own_named_in_the_study_file_is_done_and_scored_as_it_says(
    tmp_path: Path,
) -> None:
    """One participant, one trial, no practice: the squeeze ends the trial as a success (the
    pick-and-place's monitor would have called it the operator stopping before a release), with
    the gripper over the bowl where the task put it."""
    study = parse_study(
        f'task = "{OWN}"\nmodalities = ["full"]\ntimeout_s = 20.0\n'
        "[familiarization]\ntrials = 0\n"
        "[cohort]\nsize = 1\navr_experts = 0\ngames_experts = 0\nboth_experts = 0\n",
        "squeeze.toml",
    )
    run = run_study(study, tmp_path / "run", workers=1)
    assert run.ran == 1
    with open(tmp_path / "run" / "trials.csv", newline="") as f:
        (row,) = list(csv.DictReader(f))
    assert row["outcome"] == "success" and float(row["completion_time_s"]) > 0
    with open(tmp_path / "run" / row["trajectory_file"], newline="") as f:
        last = list(csv.DictReader(f))[-1]
    gripper = np.array([float(last[f"gripper_{a}_m"]) for a in "xyz"])
    bowl = np.array([float(last[f"bowl_{a}_m"]) for a in "xyz"])
    assert np.linalg.norm(gripper - bowl - [0.0, 0.0, ABOVE_M]) < 0.03


def test_a_study_names_the_pick_and_place_unless_it_says_otherwise() -> None:
    assert parse_study("seed = 1\n").task == "pick-and-place"
    assert trial_task("pick-and-place") is PICK_AND_PLACE
    assert trial_task(OWN) is SQUEEZE
    assert type(PICK_AND_PLACE.monitor(WORKSPACE)) is TaskMonitor
    assert type(SQUEEZE.monitor(WORKSPACE)) is SqueezeMonitor


@pytest.mark.parametrize(
    ("name", "message"),
    [
        ("pick and place", f"task = 'pick and place': {EXPECTED}"),
        ("tests.teleop.squeeze_task:", f"task = 'tests.teleop.squeeze_task:': {EXPECTED}"),
        (
            "tests.teleop:squeeze_task:SQUEEZE",
            f"task = 'tests.teleop:squeeze_task:SQUEEZE': {EXPECTED}",
        ),
        (".squeeze_task:SQUEEZE", f"task = '.squeeze_task:SQUEEZE': {EXPECTED}"),
        (
            "tests.teleop.exits_on_import:TASK",
            "task = 'tests.teleop.exits_on_import:TASK': the module "
            "'tests.teleop.exits_on_import' cannot be imported (SystemExit: this module ends the "
            "program); install it, put its folder on PYTHONPATH, or mend it.",
        ),
        (
            "tests.teleop.squeeze_task:NOT_A_TASK",
            "task = 'tests.teleop.squeeze_task:NOT_A_TASK': tests.teleop.squeeze_task has no "
            f"TrialTask called 'NOT_A_TASK'; {EXPECTED}",
        ),
        (
            "tests.teleop.no_such_module:SQUEEZE",
            "task = 'tests.teleop.no_such_module:SQUEEZE': the module "
            "'tests.teleop.no_such_module' cannot be imported (ModuleNotFoundError: No module "
            "named 'tests.teleop.no_such_module'); install it, put its folder on PYTHONPATH, or "
            "mend it.",
        ),
    ],
)
def test_a_task_the_study_cannot_find_is_refused_at_its_line(name: str, message: str) -> None:
    with pytest.raises(StudyDefinitionError) as err:
        parse_study(f'seed = 1\ntask = "{name}"\n', "study.toml")
    assert str(err.value) == f"study.toml line 2: {message}"


def test_a_task_site_is_what_the_task_is_made_from() -> None:
    """The pick-and-place's grasp tolerance: half the open fingers' gap less the bowl's wall."""
    task = PICK_AND_PLACE.operator_task(TaskSite(WORKSPACE, np.zeros(3), (0.0, 0.1)))
    assert task.grasp_clearance_m == pytest.approx((0.1 - WORKSPACE.bowl.wall_thickness_m) / 2)

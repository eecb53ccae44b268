"""A trial's task, as a study names it: what the simulated participant is asked to do, paired
with how the site scores it.

The operator's side of a task (its phases and goals, :class:`~arteleop.operator.Task`) knows
nothing of how a trial is judged; the site's side (a :class:`~arteleop.teleop.TaskMonitor`:
when the trial starts and ends, and whether it succeeded) knows nothing of how a person does it.
A :class:`TrialTask` pairs the two under one name, so that a study file's ``task`` key chooses
both: ``"pick-and-place"`` (the original study's), ``"pointing"`` (the simulated
participant's calibration task, a Fitts study's), or a task of one's own as
``"package.module:NAME"``, ``NAME`` a :class:`TrialTask` (docs/guides/extending.md).
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from arteleop.errors import ConfigurationError
from arteleop.operator import PickAndPlace, PointingTask, Task
from arteleop.scene import BowlTracker, Workspace
from arteleop.teleop.task_monitor import PointingMonitor, SelectionMonitor, TaskMonitor


@dataclass(frozen=True)
class TaskSite:
    """What a task is made from for one trial: the site as the participant was told of it.

    Attributes:
        workspace: The trial's table, bowl, start and target (base frame).
        rest_gripper_m: Where the gripper rests before the trial (base frame, m): the operator
            aligns its hand on it to engage.
        gripper_gap_range_m: The gripper's finger gap, closed and open (m).
    """

    workspace: Workspace
    rest_gripper_m: NDArray[np.float64]
    gripper_gap_range_m: tuple[float, float]


@dataclass(frozen=True)
class TrialTask:
    """A task a study can name: the participant's task and the site's scoring of it.

    Attributes:
        name: Its name; the platform's own are found by it (:data:`TASKS`).
        operator_task: Makes the simulated participant's task for one trial.
        monitor: Makes the trial's monitor for the trial's workspace: a
            :class:`~arteleop.teleop.TaskMonitor`, or a subclass that scores another task.
    """

    name: str
    operator_task: Callable[[TaskSite], Task]
    monitor: Callable[[Workspace], TaskMonitor]


def _pick_and_place(site: TaskSite) -> Task:
    """The bowl grasped at a rim point facing +y; the open fingers straddle its wall within half
    their gap less the wall."""
    bowl = site.workspace.bowl
    clearance_m = (site.gripper_gap_range_m[1] - bowl.wall_thickness_m) / 2
    return PickAndPlace(bowl.grasp_offset_m(), site.rest_gripper_m, clearance_m)


PICK_AND_PLACE = TrialTask(
    "pick-and-place", _pick_and_place, lambda ws: TaskMonitor(ws, BowlTracker(ws.bowl))
)
"""The original study's task: the bowl from its start into the target circle
(docs/explanation/study.md)."""


def pointing_task(workspace: Workspace, rest_gripper_m: NDArray[np.float64]) -> PointingTask:
    """The pointing task of ``workspace``: its target circle's diameter is the target's width;
    the gripper rests at ``rest_gripper_m`` (base frame, m)."""
    width_m = 2 * workspace.target_circle_radius_m
    return PointingTask(width_m=width_m, rest_gripper_m=rest_gripper_m)


def _pointing(site: TaskSite) -> Task:
    return pointing_task(site.workspace, site.rest_gripper_m)


POINTING = TrialTask("pointing", _pointing, lambda ws: PointingMonitor(ws, BowlTracker(ws.bowl)))
"""A Fitts pointing trial: from over the start cross to over the target circle, selected by
closing the gripper (:mod:`arteleop.teleop.pointing`)."""

POINTING_BY_PERSON = TrialTask(
    "pointing", _pointing, lambda ws: SelectionMonitor(ws, BowlTracker(ws.bowl))
)
"""The pointing task as a person does it, served (``arteleop study serve``): the trial ends at
the person's selection, the grip closed after the gripper was over the start cross; a simulated
participant's ends when it stops, its closures before its decision being slips. Named by
:data:`PERSON_POINTING`, not in :data:`TASKS`: a study's ``task`` is ``"pointing"`` either way."""
PERSON_POINTING = f"{__name__}:POINTING_BY_PERSON"
"""The :attr:`~arteleop.teleop.TrialConfig.task` of a person's pointing trial."""

TASKS: dict[str, TrialTask] = {PICK_AND_PLACE.name: PICK_AND_PLACE, POINTING.name: POINTING}
"""The platform's own tasks, by name."""


def trial_task(name: str) -> TrialTask:
    """The task called ``name``: one of :data:`TASKS`, or ``"package.module:NAME"``, the
    :class:`TrialTask` ``NAME`` of an importable module."""
    if name in TASKS:
        return TASKS[name]
    expected = (
        f"expected {', '.join(map(repr, TASKS))}, or a task of your own as 'package.module:NAME' "
        "(docs/guides/extending.md)"
    )
    module_name, _, attribute = name.partition(":")
    if not (
        all(part.isidentifier() for part in module_name.split(".")) and attribute.isidentifier()
    ):
        raise ConfigurationError(f"task = {name!r}: {expected}.")
    try:
        module = importlib.import_module(module_name)
    except (Exception, SystemExit) as err:  # a user's module may fail in any way while it loads
        raise ConfigurationError(
            f"task = {name!r}: the module {module_name!r} cannot be imported "
            f"({type(err).__name__}: {err}); install it, put its folder on PYTHONPATH, or mend it."
        ) from None
    found = getattr(module, attribute, None)
    if not isinstance(found, TrialTask):
        raise ConfigurationError(
            f"task = {name!r}: {module_name} has no TrialTask called {attribute!r}; {expected}."
        )
    return found

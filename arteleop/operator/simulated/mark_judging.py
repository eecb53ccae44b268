"""The marks a task may judge besides the target, each judged from a glance: the start's
cross of the pointing task (:attr:`~arteleop.operator.Task.marks`)."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import replace
from typing import TYPE_CHECKING

from arteleop.errors import ConfigurationError
from arteleop.operator.simulated.judging import Judge, Mark

if TYPE_CHECKING:
    from arteleop.operator.simulated.perception import GraspJudgement


def judge_start(judge: Judge, gripper_seen: bool, grasp: GraspJudgement) -> Mark | None:
    """The start cross, drawn in the cloud: its centre is where its arms cross, so there is no
    circle to bisect. Judged against the gripper over it; while the gripper is not shown,
    against what is (the gripper then felt, not seen). The judged start (m) with its believed
    covariance relative to the judged gripper (m^2); None where the display gives no start."""
    view = judge.view
    if view.start_m is None:
        return None
    cross = view.in_cloud(view.start_m)
    if gripper_seen:

        def against_gripper() -> Mark:
            mark, cov = judge.seen("start", cross, judge.shown_gripper, judge.cloud_grain)
            mark, cov, fixations = judge.with_aids(
                "start", cross, mark, cov, judge.cloud_grain, read_height=True
            )
            return Mark(grasp.gripper_m + mark - judge.shown_gripper, cov, fixations)

        return judge.mark("start", view.start_drawn, judge.shown_gripper, against_gripper)
    mark_point = view.target_m if view.cues.target_mesh else view.in_cloud(view.target_m)
    against = view.bowl_m if view.bowl_m is not None else mark_point

    def against_scene() -> Mark:
        start, mark_cov = judge.seen("start", cross, against, judge.cloud_grain)
        return Mark(start, mark_cov, judge.fixated(cross, against))

    seen = judge.mark("start", view.start_drawn, against, against_scene)
    return replace(seen, cov=seen.cov + grasp.cov)


MARK_JUDGEMENTS: dict[str, Callable[[Judge, bool, GraspJudgement], Mark | None]] = {
    "start": judge_start,
}
"""The marks a task may judge besides the target (:attr:`~arteleop.operator.Task.marks`), each
from one glance: who judges it, given the glance, whether the gripper is shown, and the
gripper's judgement."""


def judgeable_marks(names: Sequence[str]) -> tuple[str, ...]:
    """A task's :attr:`~arteleop.operator.Task.marks`, each one of :data:`MARK_JUDGEMENTS`:
    checked once, when the operator is given the task, not at every glance."""
    for name in names:
        if name not in MARK_JUDGEMENTS:
            raise ConfigurationError(
                f"The task judges a mark {name!r}; the display draws {', '.join(MARK_JUDGEMENTS)}."
            )
    return tuple(names)

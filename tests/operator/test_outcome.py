"""What the simulated participant sees of a trial's outcome: a miss it is sure of, and only that."""

from dataclasses import replace

import numpy as np
import pytest

from arteleop.ar_features import ArCues
from arteleop.operator import (
    ArmModel,
    CalibrationPosture,
    OperatorParams,
    OperatorTraits,
    Perceived,
    PickAndPlace,
    PointingTask,
    SyntheticOperator,
)
from arteleop.operator.simulated.criterion import PhaseCriterion
from arteleop.operator.simulated.outcome import sure_missed
from arteleop.scene import BowlSpec
from arteleop.transforms import make_transform
from tests.ar_features.frames import display_frame

TARGET = np.array([0.70, -0.20, 0.0])
TRAITS = OperatorTraits()  # stops within 10 mm of the target, 95 % sure


def _resting(off_m: float, sd_m: float) -> Perceived:
    """A last look at the bowl resting ``off_m`` (m) from the target along y, judged with an SD
    of ``sd_m`` (m) per axis, the hand 10 cm up and away from it after letting go."""
    bowl = TARGET + [0.0, off_m, 0.0]
    cov = np.eye(3) * sd_m**2
    return Perceived(bowl + [0.0, 0.08, 0.12], bowl, TARGET, True, True, cov, cov, False)


def test_a_miss_the_display_shows_clearly_is_seen_and_one_it_blurs_is_not() -> None:
    task = PickAndPlace(BowlSpec().grasp_offset_m(), np.zeros(3))
    assert sure_missed(task, _resting(0.017, 0.003), TRAITS, 1.0, {})
    assert not sure_missed(task, _resting(0.002, 0.003), TRAITS, 1.0, {})
    # The same 17 mm judged with an SD of 10 mm: the person cannot tell it missed.
    assert not sure_missed(task, _resting(0.017, 0.010), TRAITS, 1.0, {})
    # Having learnt that its judgement is worse than it believed (four times the variance: SD
    # 6 mm), it is no longer sure of the 17 mm miss it sees at 3 mm.
    assert not sure_missed(task, _resting(0.017, 0.003), TRAITS, 4.0, {})


def test_what_a_person_settled_for_is_no_miss_to_it() -> None:
    task = PickAndPlace(BowlSpec().grasp_offset_m(), np.zeros(3))
    seen = _resting(0.012, 0.001)
    assert sure_missed(task, seen, TRAITS, 1.0, {})  # 12 mm against 10: surely out
    assert not sure_missed(task, seen, replace(TRAITS, placement_criterion_m=0.02), 1.0, {})
    # Placed once its criterion had loosened to 15 mm with the effort spent: no miss.
    assert not sure_missed(task, seen, TRAITS, 1.0, {"lower": 0.015})
    assert sure_missed(task, seen, TRAITS, 1.0, {"transport": 0.015})


def test_a_task_without_an_outcome_to_judge_sees_no_miss() -> None:
    """Pointing tells its misses (the selection in the circle or not); a task may say None."""
    seen = _resting(0.030, 0.001)
    pointing = PointingTask(width_m=0.02, rest_gripper_m=np.zeros(3))
    assert not sure_missed(pointing, seen, TRAITS, 1.0, {})
    told = PickAndPlace(BowlSpec().grasp_offset_m(), np.zeros(3))
    told.outcome_phase = None  # type: ignore[assignment]
    assert not sure_missed(told, seen, TRAITS, 1.0, {})


def test_the_last_look_judges_the_bowl_drawn_against_the_target_mesh() -> None:
    """Through the operator, on display frames: the bowl let go on the target mesh, or 30 mm off
    it, the gripper risen 10 cm above it."""
    task = PickAndPlace(BowlSpec().grasp_offset_m(), np.zeros(3))
    rng = np.random.default_rng(0)
    operator = SyntheticOperator(task, lambda p: p, ArmModel(), CalibrationPosture(), rng,
                                 OperatorParams(), TRAITS)  # fmt: skip

    def resting(off_m: float):
        bowl = np.array([0.68, -0.10 + off_m, -0.2])
        gripper = make_transform(np.diag([1.0, -1.0, -1.0]), bowl + [0.0, 0.078, 0.155])
        cues = ArCues(target_mesh=True)
        return display_frame(bowl_m=bowl, T_base_gripper=gripper, cues=cues)

    assert not operator.saw_miss(resting(0.0))
    assert operator.saw_miss(resting(0.030))


def test_the_criterion_a_phase_was_accepted_at_is_kept_loosened_by_the_effort_spent() -> None:
    task = PickAndPlace(BowlSpec().grasp_offset_m(), np.zeros(3))
    criterion = PhaseCriterion(task, TRAITS, OperatorParams())
    lower = next(p for p in task.phases if p.name == "lower")
    criterion.enter(lower)
    criterion.arrived(2.0)
    criterion.accept(6.0)  # 4 s of correcting at urgency 8 s: half as loose again
    assert criterion.accepted_m == {"lower": pytest.approx(0.010 * 1.5)}

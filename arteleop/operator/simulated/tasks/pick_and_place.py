"""The original study's task: pick the bowl up from its start and place it on the target."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from arteleop.operator.simulated.bowl_memory import BowlMemory
from arteleop.operator.simulated.perception import Perceived
from arteleop.operator.simulated.tasks.task import (
    Action,
    Goal,
    TaskPhase,
    planar_goal,
    relative_goal,
)
from arteleop.operator.simulated.traits import OperatorTraits

REACH = TaskPhase("reach")  # above the grasp point
DESCEND = TaskPhase("descend")  # onto it, the open fingers either side of the wall
CLOSE = TaskPhase("close", Action.CLOSE)
LIFT = TaskPhase("lift")
TRANSPORT = TaskPhase("transport")  # the bowl over the target
LOWER = TaskPhase("lower")  # onto it
OPEN = TaskPhase("open", Action.OPEN)
RETRACT = TaskPhase("retract")  # straight up from where the hand let go, to clear the bowl
HOME = TaskPhase("home")  # back to rest: the arm leaves the camera's view of the bowl
_GRASP = (REACH, DESCEND)
_PLACE = (TRANSPORT, LOWER)
_CARRY = (LIFT, TRANSPORT, LOWER)  # the bowl should be in the hand
_UP = np.array([0.0, 0.0, 1.0])


class PickAndPlace:
    """What the person knows of the pick-and-place from instructions and familiarisation (base
    frame), and what they remember while doing it.

    The grasp is judged relative to the bowl, its criterion the fingers' clearance around the
    wall times the person's share of it; the placement in the table's plane against the
    target, its criterion the person's own. Carrying, the person puts the bowl it sees (or
    remembers, where the arm hides it) over the target it sees; if a look shows the bowl left
    on the table, it goes back for it.

    Args:
        grasp_offset_m: Grasp point relative to the bowl's bottom centre (a point of the rim).
        rest_gripper_m: Where the gripper waits at rest, to align the hand before engaging.
        grasp_clearance_m: How far the gripper may be off the grasp point with the open fingers
            still either side of the wall (m): half the open fingers' gap less the wall.
        approach_height_m: Height above the grasp or place point to approach from (m).
        carry_height_m: Height of the bowl's transport above the table (m).
    """

    phases = (REACH, DESCEND, CLOSE, LIFT, TRANSPORT, LOWER, OPEN, RETRACT, HOME)
    ends_trial = False
    aims_gripper = False
    marks: tuple[str, ...] = ()
    outcome_phase = LOWER  # the bowl resting off the target is a miss the person can see

    def __init__(
        self,
        grasp_offset_m: ArrayLike,
        rest_gripper_m: ArrayLike,
        grasp_clearance_m: float = 0.019,
        approach_height_m: float = 0.10,
        carry_height_m: float = 0.15,
    ) -> None:
        self.grasp_offset_m = np.asarray(grasp_offset_m, dtype=np.float64)
        self.rest_gripper_m = np.asarray(rest_gripper_m, dtype=np.float64)
        self.grasp_clearance_m = grasp_clearance_m
        self.approach_height_m = approach_height_m
        self.carry_height_m = carry_height_m
        self.memory = BowlMemory()
        self._grasped_at: NDArray[np.float64] | None = None
        self._released_at: NDArray[np.float64] | None = None

    def criterion_m(self, phase: TaskPhase, traits: OperatorTraits) -> float | None:
        if phase in _GRASP:
            return self.grasp_clearance_m * traits.grasp_criterion_scale
        if phase in _PLACE:
            return traits.placement_criterion_m
        return None

    def goal(self, phase: TaskPhase, seen: Perceived) -> Goal | None:
        bowl = self.memory.bowl_m(seen)
        if bowl is None:
            return None
        grasp = bowl + self.grasp_offset_m
        if phase in _GRASP:
            above = grasp + _UP * self.approach_height_m
            return relative_goal(above if phase is REACH else grasp, seen)
        # Carrying, the person puts the bowl it sees (or remembers) over the target it sees.
        place = seen.gripper_m + seen.target_m - bowl
        place[2] = seen.target_m[2] + self.grasp_offset_m[2] + 0.005
        if phase in _PLACE:
            above = place + _UP * self.carry_height_m
            held = self.memory.in_hand_cov if self.memory.holding else None
            return planar_goal(above if phase is TRANSPORT else place, seen, held)
        lift_from = self._grasped_at if self._grasped_at is not None else grasp
        retract_from = self._released_at if self._released_at is not None else place
        gripper = {
            LIFT.name: lift_from + _UP * self.carry_height_m,
            RETRACT.name: retract_from + _UP * self.approach_height_m,
            HOME.name: self.rest_gripper_m,
        }[phase.name]
        return relative_goal(gripper, seen)

    def gripped(self, phase: TaskPhase, seen: Perceived) -> None:
        bowl = self.memory.bowl_m(seen)
        if phase.action is Action.CLOSE:
            self._grasped_at = seen.gripper_m
            self.memory.grasp(seen, bowl)
        else:
            self._released_at = seen.gripper_m
            self.memory.release()

    def setback(self, phase: TaskPhase, seen: Perceived) -> str | None:
        if phase not in _CARRY or not self.memory.left_behind(seen):
            return None
        # The bowl stayed on the table: reach for it again, where it was seen just now.
        self.memory.release()
        self.memory.bowl_m(seen)
        self._grasped_at = None
        return REACH.name

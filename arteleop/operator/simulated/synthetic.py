"""A synthetic operator who does a task through the teleoperation system: a model of a person,
not a replayed path (docs/explanation/operator-model.md gives every constant with its source).

What is to be done is the task's (:mod:`arteleop.operator.simulated.tasks`); how, the
operator's, the same for every task. It **moves** in minimum-jerk submovements timed to minimise
the expected time to the criterion (:mod:`.submovements`), **watches** the display until the
gripper it shows is still (:mod:`.watch`), **looks**, glance after glance, until it is sure
either way (:mod:`.look`, :mod:`.perception`, :mod:`.belief`), and **homes in** during a movement
where the display shows the gripper and the goal, with corrections spaced so that each one's
effect is on the display before the next (intermittent control), predicting from its efference
copy over the lag it believes; after the task it sees whether it missed (:mod:`.outcome`). A cue
changes it only through what the display lets it see. Its output: a hand pose and a grip.
"""

from __future__ import annotations

from collections.abc import Callable
from enum import Enum

import numpy as np
from numpy.typing import NDArray

from arteleop.ar_features import DisplayFrame
from arteleop.moved import moved_names
from arteleop.operator.output import ALIGN, CALIBRATE, DONE, ENGAGE, OperatorOutput
from arteleop.operator.simulated.criterion import PhaseCriterion
from arteleop.operator.simulated.hand import Hand, HandMap, Tremor, Wrist, felt_apart, ramped_grip
from arteleop.operator.simulated.look import Look
from arteleop.operator.simulated.mark_memory import MarkMemory
from arteleop.operator.simulated.outcome import sure_missed
from arteleop.operator.simulated.params import OperatorParams
from arteleop.operator.simulated.perception import Perceived, judgeable_marks, perceive
from arteleop.operator.simulated.perceptual_errors import PerceptualErrors
from arteleop.operator.simulated.phase_log import PhaseLog, PhaseRecord
from arteleop.operator.simulated.submovements import planned_submovement
from arteleop.operator.simulated.tasks import Action, Goal, Task, TaskPhase, phase_named
from arteleop.operator.simulated.traits import OperatorTraits
from arteleop.operator.simulated.watch import DisplayWatch
from arteleop.operator.wearable.arm_model import ArmModel
from arteleop.operator.wearable.posture import CalibrationPosture, hand_from_calibration


class _Mode(Enum):
    MOVE = "move"  # submovements under way
    WATCH = "watch"  # the hand has stopped: wait for the display to show the gripper still
    LOOK = "look"  # glance after glance at the error
    WAIT = "wait"  # a fixed wait (grip, motor delay)


class SyntheticOperator:
    """Closed-loop synthetic operator doing ``task``. Call :meth:`step` at the wearable's rate."""

    def __init__(
        self,
        task: Task,
        hand_for_gripper: Callable[[NDArray[np.float64]], NDArray[np.float64]],
        arm: ArmModel,
        calibration: CalibrationPosture,
        rng: np.random.Generator,
        params: OperatorParams | None = None,
        traits: OperatorTraits | None = None,
    ) -> None:
        """``hand_for_gripper(p)`` maps a gripper position to the hand position that commands it."""
        self.p = params or OperatorParams()
        self.traits = traits or OperatorTraits()
        self.task = task
        self._judged = judgeable_marks(getattr(task, "marks", ()))  # optional in one's own
        self._map = HandMap(hand_for_gripper)
        self._rng = rng
        calib_pos, turn = hand_from_calibration(arm, calibration, self.p.hand_pitch_rad)
        self._wrist = Wrist(turn, self.p.hand_pitch_rad)
        self.phase = CALIBRATE
        self._task_phase: TaskPhase | None = None  # the task's phase under way, if any
        self._log = PhaseLog()
        self._mode = _Mode.WAIT
        self._wait_until = calibration.hold_s + 0.2
        self.hand = Hand(calib_pos)
        self._grip = 0.0
        self._criterion = PhaseCriterion(task, self.traits, self.p)
        self._tremor = Tremor(self.p.tremor_amplitude_m, self.p.tremor_hz, rng)
        self._errors = PerceptualErrors(rng, self.traits.bias_seed, self.p.perception.bias_share)
        self._marks = MarkMemory(self.p.perception)
        self._watch = DisplayWatch(self.p)
        self._look = Look(self.traits, self.p.max_look_s)
        self._glancing: tuple[Perceived, Goal | None] | None = None  # a look's glance under way
        self._last_amend_s = -np.inf
        # In-flight corrections are made over the primary's second half, its deceleration.
        self._homing_from_s = self._homing_until_s = 0.0
        self._moved_in_phase = False
        self._last_step_s: float | None = None
        self.corrections_total = 0
        """Corrective submovements, in flight or after a look."""
        self.looks_total = 0

    @property
    def history(self) -> list[PhaseRecord]:
        """Every pass through one of the task's phases, in order."""
        return self._log.records

    @property
    def lag_s(self) -> float:
        """The display's lag as the operator has come to perceive it (s)."""
        return self._watch.lag_s

    @property
    def movement_start_s(self) -> float | None:
        """Start time (s) of the movement under way; None between movements."""
        return self.hand.moves[0].start_s if self.hand.moves else None

    def saw_miss(self, view: DisplayFrame) -> bool:
        """Whether a look at the display the trial ended on shows a sure miss (:mod:`.outcome`)."""
        self._errors.new_look()
        c = self._criterion
        return sure_missed(self.task, self._glance(view), self.traits, c.error_scale, c.accepted_m)

    def stopped(self, time_s: float) -> bool:
        """Whether the task, one that ends the trial, is done, its last wait over at ``time_s``."""
        return self.task.ends_trial and self.phase == DONE and time_s >= self._wait_until

    def start_phase(self, name: str, hand_m: NDArray[np.float64], time_s: float) -> None:
        """Put the operator, engaged, at the start of the task's phase ``name`` with its hand
        at ``hand_m`` (torso frame, m) at ``time_s`` (s): to study one phase on its own."""
        self.hand = Hand(np.asarray(hand_m, dtype=np.float64))
        self._last_step_s = None
        self._enter(phase_named(self.task, name), time_s)
        self._mode, self._wait_until = _Mode.WAIT, time_s

    # -- what the operator knows ---------------------------------------------------------------
    def _timed_s(self, interval_s: float) -> float:
        """An interval (s) as the operator times it, once: people time intervals with a
        variability proportional to their length (scalar timing)."""
        return interval_s * max(0.0, 1.0 + self.p.timing_weber * self._rng.normal())

    def _look_cost_s(self) -> float:
        """What one more look costs, as the operator has come to know it (s)."""
        p = self.p
        return p.arrival_window_s + self.lag_s + self._look.cost_s + p.motor_delay_s

    # -- moving ----------------------------------------------------------------------------------
    def _move(self, t: float, hand_delta: NDArray[np.float64], start_s: float) -> None:
        """Add a submovement of the hand by ``hand_delta`` (m) from ``start_s`` (s), timed by the
        planner, its endpoint scattered by its speed."""
        move = planned_submovement(
            hand_delta, start_s, self._criterion.at(t), self._look_cost_s(), self.p,
            self.traits.movement_time_factor, self._rng,
        )  # fmt: skip
        self.hand.add(move)
        self._mode = _Mode.MOVE
        self._log.moved(start_s)

    # -- seeing ----------------------------------------------------------------------------------
    def _glance(self, view: DisplayFrame) -> Perceived:
        t = self.traits
        return perceive(
            view, self.p.perception, self._errors, t.depth_factor, t.depth_scale,
            self.task.aims_gripper, self._marks, self._judged,
        )  # fmt: skip

    def _glance_s(self, goal: Goal | None) -> float:
        """How long a glance at ``goal`` takes (s): a perceptual cycle, and an eye movement for
        each further fixation the judgement needs (one, where nothing is shown yet)."""
        extra = 0 if goal is None else goal.fixations - 1
        return self.traits.glance_s + extra * self.p.perception.eye_movement_s

    # -- deciding --------------------------------------------------------------------------------
    def _start_look(self, t: float) -> None:
        self._mode = _Mode.LOOK
        self._errors.new_look()
        self._look.start(t)
        self._glancing = None
        self.looks_total += 1
        self._log.looked(t)

    def _take_glance(self, t: float, view: DisplayFrame) -> None:
        """A look's glances, one after the other: each sees the display as it is when it
        begins and is judged when its fixations are over; decide once sure enough either way,
        else glance again."""
        phase = self._task_phase
        assert phase is not None  # looks are at the task's goals
        if self._glancing is not None:
            seen, goal = self._glancing
            self._glancing = None
            self._judge(t, phase, seen, goal)
            if self._mode is not _Mode.LOOK:
                return
        seen = self._glance(view)
        goal = self.task.goal(phase, seen)
        self._glancing = (seen, goal)
        self._look.glanced(t, self._glance_s(goal))

    def _judge(self, t: float, phase: TaskPhase, seen: Perceived, goal: Goal | None) -> None:
        """What a glance that ends at ``t`` (s) showed: accept, correct, set back, or nothing
        (look again)."""
        if goal is None:  # not shown yet: keep looking
            return
        # However often it went wrong, a person who sees it goes back, until the trial's time
        # is up: nobody carries an empty gripper on.
        back = self.task.setback(phase, seen)
        if back is not None:
            self._set_back(t, back)
            return
        if self._felt_beyond(seen):
            # The gripper shown has stopped and the hand is felt well beyond it: the operator
            # brings the hand to where it commands the goal, as it aligned it, from memory.
            self._correct(t, goal.gripper_m - self._map.gripper_m(self.hand.position_m))
            return
        error = goal.gripper_m - seen.gripper_m
        sure = self._criterion.sure_within(t, error, goal)
        within = self._criterion.sure_within(t, error, goal, np.zeros((3, 3))) == 1.0
        accept = self._look.verdict(t, sure, float(np.trace(goal.cov_m2)), within)
        if accept is None:  # not sure either way: look again
            return
        if accept:
            self._criterion.accept(t)
            self._advance(t)
        else:
            self._correct(t, error)

    def _felt_beyond(self, seen: Perceived) -> bool:
        """The display says the arm has stopped, and the hand is felt to command the gripper
        beyond where it is shown (a gap of a few centimetres is not felt)."""
        if not seen.arm_stopped:  # every glance asks: the map only while the notice is on
            return False
        gap_m = self._map.gripper_m(self.hand.position_m) - seen.gripper_m
        sd_m = self.p.perception.proprioception_sd_m
        return felt_apart(gap_m, sd_m, self.traits.confidence)

    def _correct(self, t: float, error: NDArray[np.float64]) -> None:
        if self.hand.moving:
            return
        if self._moved_in_phase:
            self.corrections_total += 1
        self._moved_in_phase = True
        self._move(t, self._map.hand_per_gripper @ error, t + self.p.motor_delay_s)
        primary = self.hand.moves[-1]
        self._homing_from_s = primary.start_s + 0.5 * primary.duration_s
        self._homing_until_s = primary.start_s + primary.duration_s
        self._watch.await_response(
            error,
            visible_at_s=primary.time_to_cover_s(self.p.motion_threshold_m),
            half_at_s=self._homing_from_s,
        )

    def _home_in(self, t: float, view: DisplayFrame) -> None:
        """A glance during a movement: correct in flight where the display shows the gripper
        and the goal. Corrections are intermittent: the next waits until the last one's effect
        is on the display as the operator believes its delay (visuomotor and display), so a long
        lag leaves room for few, and the operator moves and waits."""
        p = self.p
        phase = self._task_phase
        if (
            phase is None
            or self._criterion.task_m() is None
            or t < self._look.next_glance_s
            # A correction's effect must be on the display before the next one is planned.
            or t < self._last_amend_s + p.visuomotor_delay_s + self.lag_s
            or not self._homing_from_s <= t < self._homing_until_s
        ):
            return
        self._errors.new_look()
        seen = self._glance(view)
        goal = self.task.goal(phase, seen)
        self._look.glanced(t, self._glance_s(goal))
        if goal is None or not goal.visible or self._felt_beyond(seen):  # nothing to predict from
            return
        # Where the gripper will end: as seen now, plus what the hand did over the lag the
        # operator believes the display has (timed as people time intervals), plus what the hand
        # has still to do. A lag longer than it believes makes the prediction fall short, and
        # the correction overshoot. It knows how uncertain that is beyond the glance (its
        # timing, its motor noise), and so does not chase a miss its prediction could make.
        to_end, to_end_cov = self.hand.to_end(
            t, self.lag_s, self._timed_s(self.lag_s), p.timing_weber
        )
        to_gripper = self._map.gripper_per_hand
        error = goal.gripper_m - (seen.gripper_m + to_gripper @ to_end)
        cov = goal.cov_m2 + to_gripper @ to_end_cov @ to_gripper.T
        # As after a look, it corrects what it is sure will miss.
        if self._criterion.sure_within(t, error, goal, cov) > 1 - self.traits.confidence:
            return
        self.corrections_total += 1
        self._last_amend_s = t
        self._move(t, self._map.hand_per_gripper @ error, t + p.motor_delay_s)

    def _set_back(self, t: float, name: str) -> None:
        """A look shows the task went wrong: open the hand and go back to phase ``name``."""
        self._grip = 0.0
        self._enter(phase_named(self.task, name), t)
        self._mode, self._wait_until = _Mode.WAIT, t + self.p.grip_ramp_s

    def _enter(self, phase: TaskPhase | str, t: float) -> None:
        """Begin one of the task's phases, or one of the operator's own (a name)."""
        task_phase = phase if isinstance(phase, TaskPhase) else None
        self._log.enter(None if task_phase is None else task_phase.name, t)
        self._task_phase = task_phase
        self.phase = phase if task_phase is None else task_phase.name
        self._criterion.enter(task_phase)
        self._moved_in_phase = False

    def _advance(self, t: float) -> None:
        """The phase is done: the next one, after the motor delay or the grip's ramp."""
        phases = self.task.phases
        k = phases.index(self._task_phase) + 1 if self._task_phase is not None else len(phases)
        self._enter(phases[k] if k < len(phases) else DONE, t)
        self._mode = _Mode.WAIT
        grips = self._task_phase is not None and self._task_phase.action is not Action.MOVE
        self._wait_until = t + (self.p.grip_ramp_s if grips else self.p.motor_delay_s)

    # -- acting ----------------------------------------------------------------------------------
    def step(self, time_s: float, view: DisplayFrame) -> OperatorOutput:
        """The hand's pose and the grip at ``time_s`` (s), the sample's own time.

        ``view`` is the newest display content that has reached the operator, which is older
        than ``time_s`` by the camera period and the return link's delay: it informs the
        operator's decisions, never the time at which the hand is evaluated.
        """
        t = time_s
        if self._last_step_s is not None:  # since the last sample, it did what it was doing
            self._log.spent(self._mode.value, self._last_step_s, t)
        self._last_step_s = t
        self._watch.see(t, view)
        moves_in_task = self._task_phase is not None and self._task_phase.action is Action.MOVE
        if self._mode is _Mode.MOVE:
            self.hand.advance(t)
        # after the advance: the path's sample at t must be where the hand was meant to be at t
        self.hand.remember(t)
        if self._mode is _Mode.MOVE:
            if self.hand.moving:
                if moves_in_task:
                    self._home_in(t, view)
            else:
                self._watch.hand_stopped(t, self._timed_s(self.lag_s))
                self._mode = _Mode.WATCH
        elif self._mode is _Mode.WATCH:
            if not moves_in_task:
                self._decide(t, view)
            elif self._watch.arrived(t):
                self._criterion.arrived(t)
                self._start_look(t)
        elif self._mode is _Mode.LOOK:
            if t >= self._look.next_glance_s:
                self._take_glance(t, view)
        elif t >= self._wait_until:
            self._decide(t, view)
        return self._output(t)

    def _decide(self, t: float, view: DisplayFrame) -> None:
        phase = self._task_phase
        if self.phase == CALIBRATE:
            self._enter(ALIGN, t)
            self._align(t)
        elif self.phase == ALIGN:
            self._enter(ENGAGE, t)
            self._mode = _Mode.WAIT
            self._wait_until = t + 0.5
        elif self.phase == ENGAGE:
            if view.engaged:
                first = self.task.phases[0]
                self._enter(first, t)
                if first.action is Action.MOVE:
                    self._start_look(t)
                else:
                    self._mode, self._wait_until = _Mode.WAIT, t
            else:  # the indicator stays off: align the hand again, from memory of the pose
                self._enter(ALIGN, t)
                self._align(t)
        elif phase is None:  # done
            return
        elif phase.action is Action.MOVE:
            self._start_look(t)
        else:
            self._grip = 1.0 if phase.action is Action.CLOSE else 0.0
            self._errors.new_look()
            seen = self._glance(view)
            self.task.gripped(phase, seen)
            wait = self.p.grip_wait_known_s if seen.closure_known else self.p.grip_wait_unknown_s
            self._advance(t)
            self._wait_until = t + wait

    def _align(self, t: float) -> None:
        """Bring the hand to where it commands the resting gripper, from memory of the pose."""
        self._move(t, self._map.hand_m(self.task.rest_gripper_m) - self.hand.position_m, t)

    def _output(self, t: float) -> OperatorOutput:
        tremor = self._tremor.at(t)
        if self.phase == CALIBRATE:
            tremor = np.zeros(3)  # the posture is held against a support during calibration
        grip, phase = self._grip, self._task_phase
        if phase is not None and phase.action is not Action.MOVE:  # ramped over the grip's wait
            squeezed = 1.0 if phase.action is Action.CLOSE else 0.0
            grip = ramped_grip(grip, squeezed, t, self._wait_until, self.p.grip_ramp_s)
        rot = self._wrist.rotation(self.phase, self.hand, t)
        return OperatorOutput(
            t, self.hand.position_m + tremor, rot, float(np.clip(grip, 0.0, 1.0)), self.phase
        )


__getattr__ = moved_names(
    "arteleop.operator.synthetic", {"TaskGeometry": "arteleop.operator:PickAndPlace"}, "0.3"
)

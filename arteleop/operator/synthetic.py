"""A synthetic operator who does the pick-and-place through the teleoperation system.

It is a model of a person, not a replayed path (docs/operator-model.md gives every constant with
its source). Each phase of the task has a goal and an accuracy criterion of the person's own; the
operator:

- **moves** in minimum-jerk submovements whose endpoints scatter in proportion to their speed,
  each one's duration chosen to minimise the expected time to the criterion, looks included
  (:mod:`arteleop.operator.submovements`): a costly look makes it move more carefully;
- **watches** the display until the gripper it shows has been still for a short window;
- **looks**, glance after glance, averaging the fresh part of its judgement errors
  (:mod:`arteleop.operator.perception`), until it is sure enough either way: it stops
  correcting when the probability that the error is within its criterion reaches its confidence
  (:mod:`arteleop.operator.belief`), a criterion that loosens with the phase's effort (urgency);
- **homes in** during a movement when the display shows both the gripper and the goal and the
  display's lag is short: it predicts where the movement will end and adds a correction in flight;
  under a longer lag it moves and waits. It acts on what it sees, which is a round trip old, so a
  correction planned in flight on a lagging view overshoots.

A cue changes the operator only through what it lets it see. Its output is a hand pose in the
torso frame and a grip value; the loop turns them into IMU signals through the arm model.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field
from enum import Enum

import numpy as np
from numpy.typing import NDArray
from scipy.spatial.transform import Rotation

from arteleop.ar_features import DisplayFrame
from arteleop.checks import Bounds, check_fields
from arteleop.operator.arm_model import ArmModel
from arteleop.operator.belief import averaging_saturated, probability_within
from arteleop.operator.minimum_jerk import minimum_jerk_profile
from arteleop.operator.perception import (
    BowlMemory,
    Perceived,
    PerceptionParams,
    PerceptualErrors,
    perceive,
    shown_gripper_m,
)
from arteleop.operator.posture import CalibrationPosture, hand_from_calibration
from arteleop.operator.submovements import submovement_duration_s
from arteleop.operator.traits import OperatorTraits

MIN_JERK_PEAK = 1.875
"""Peak speed of a minimum-jerk movement, in units of its mean speed."""


@dataclass(frozen=True)
class OperatorParams:
    """The synthetic operator's constants, the same for every person (docs/operator-model.md).

    Attributes:
        noise_k_s: Endpoint SD per axis per unit of mean speed (s): SD = k A / D.
        noise_floor_m: Endpoint SD per axis of the slowest movement (m).
        peak_speed_m_s: Fastest peak speed of the hand (m/s).
        tremor_amplitude_m: Physiological tremor per axis (m).
        tremor_hz: Its two components (Hz).
        motor_delay_s: From a decision to the start of the movement (s).
        visuomotor_delay_s: From a glance during a movement to the correction it starts (s).
        arrival_window_s: The display must show the gripper still this long (s)...
        arrival_speed_m_s: ...moving at most this fast (m/s), for it to have arrived.
        arrival_timeout_s: After the hand stops, the operator looks anyway after this (s).
        familiar_lag_s: The display's lag the operator knows from practice on the system
            (s): its first estimate of the lag, before a trial shows it another.
        move_and_wait_lag_s: Above this display lag (s) the operator no longer corrects in
            flight; it moves and waits.
        gross_criterion_m: Criterion of the movements without a precision demand (lift,
            retract, home; m).
        max_look_s: A look ends by then, sure or not (s).
        max_regrasps: Times the operator goes back for a bowl a missed grasp left behind.
        grip_ramp_s: Time to squeeze or release the pinch sensor (s).
        grasp_wait_known_s: Wait after closing when the closure is visible (s).
        grasp_wait_unknown_s: Wait when it is not: the operator must infer it (s).
        approach_height_m: Height above the grasp or place point to approach from (m).
        carry_height_m: Height of the bowl's transport above the table (m).
        hand_pitch_rad: Pitch of the hand (about torso y) while working (rad).
        perception: Perception's constants.
    """

    noise_k_s: float = 0.012
    noise_floor_m: float = 0.0021
    peak_speed_m_s: float = 0.5
    tremor_amplitude_m: float = 0.0003
    tremor_hz: tuple[float, float] = (9.0, 11.0)
    motor_delay_s: float = 0.07
    visuomotor_delay_s: float = 0.12
    arrival_window_s: float = 0.25
    arrival_speed_m_s: float = 0.02
    arrival_timeout_s: float = 3.0
    familiar_lag_s: float = 0.3
    move_and_wait_lag_s: float = 0.6
    gross_criterion_m: float = 0.05
    max_look_s: float = 1.5
    max_regrasps: int = 2
    grip_ramp_s: float = 0.3
    grasp_wait_known_s: float = 0.4
    grasp_wait_unknown_s: float = 1.0
    approach_height_m: float = 0.10
    carry_height_m: float = 0.15
    hand_pitch_rad: float = 0.4
    perception: PerceptionParams = field(default_factory=PerceptionParams)

    def __post_init__(self) -> None:
        positive, non_negative = Bounds(0, above=True), Bounds(0)
        check_fields(self, {
            **dict.fromkeys(("noise_k_s", "peak_speed_m_s", "arrival_window_s",
                             "arrival_speed_m_s", "arrival_timeout_s", "gross_criterion_m",
                             "max_look_s", "grip_ramp_s"), positive),
            **dict.fromkeys(("noise_floor_m", "motor_delay_s", "visuomotor_delay_s",
                             "familiar_lag_s"), non_negative),
        })  # fmt: skip


class Phase(Enum):
    CALIBRATE = "calibrate"
    ALIGN = "align"
    ENGAGE = "engage"
    REACH = "reach"
    DESCEND = "descend"
    CLOSE = "close"
    LIFT = "lift"
    TRANSPORT = "transport"
    LOWER = "lower"
    OPEN = "open"
    RETRACT = "retract"
    HOME = "home"
    DONE = "done"


_GRASP = (Phase.REACH, Phase.DESCEND)
_PLACE = (Phase.TRANSPORT, Phase.LOWER)
_MOVES = (*_GRASP, Phase.LIFT, *_PLACE, Phase.RETRACT, Phase.HOME)


class _Mode(Enum):
    MOVE = "move"  # submovements under way
    WATCH = "watch"  # the hand has stopped: wait for the display to show the gripper still
    LOOK = "look"  # glance after glance at the error
    WAIT = "wait"  # a fixed wait (grip, motor delay)


@dataclass(frozen=True)
class OperatorOutput:
    """The operator's hand at one sample: torso frame."""

    time_s: float
    hand_m: NDArray[np.float64]
    R_torso_hand: NDArray[np.float64]
    grip: float
    phase: Phase


@dataclass(frozen=True)
class TaskGeometry:
    """What the operator knows of the task from instructions and familiarisation (base frame).

    Attributes:
        grasp_offset_m: Grasp point relative to the bowl's bottom centre (a point of the rim).
        rest_gripper_m: Where the gripper waits at rest, to align the hand before engaging.
        grasp_clearance_m: How far the gripper may be off the grasp point with the open fingers
            still either side of the wall (m): half the open fingers' gap less the wall.
    """

    grasp_offset_m: NDArray[np.float64]
    rest_gripper_m: NDArray[np.float64]
    grasp_clearance_m: float = 0.019


@dataclass
class _Submovement:
    start_s: float
    delta_m: NDArray[np.float64]
    duration_s: float

    def done_at(self, t: float) -> NDArray[np.float64]:
        """The share of ``delta_m`` covered at ``t`` (s)."""
        return self.delta_m * float(minimum_jerk_profile((t - self.start_s) / self.duration_s))


class SyntheticOperator:
    """Closed-loop synthetic operator. Call :meth:`step` at the wearable's rate."""

    def __init__(
        self,
        task: TaskGeometry,
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
        self._to_hand = hand_for_gripper
        self._rng = rng
        calib_pos, self._rot_path = hand_from_calibration(arm, calibration, self.p.hand_pitch_rad)
        self._work_R = Rotation.from_euler("y", self.p.hand_pitch_rad).as_matrix()
        self._phases = list(Phase)
        self.phase = Phase.CALIBRATE
        self._mode = _Mode.WAIT
        self._wait_until = calibration.hold_s + 0.2
        self._base = calib_pos.copy()  # the hand where every finished submovement left it
        self._moves: list[_Submovement] = []
        self._hand = calib_pos.copy()
        self._grip = 0.0
        self._correcting_from_s: float | None = None  # the primary's arrival in this phase
        self._tremor_phase = rng.uniform(0, 2 * np.pi, (2, 3))
        self._grasped_at: NDArray[np.float64] | None = None
        self._released_at: NDArray[np.float64] | None = None
        self._memory = BowlMemory()
        self._errors = PerceptualErrors(rng, self.traits.bias_seed, self.p.perception.bias_share)
        self._shown: deque[tuple[float, NDArray[np.float64] | None]] = deque()
        self._hands: deque[tuple[float, NDArray[np.float64]]] = deque()  # its own recent hand
        self._hand_stop_s = 0.0
        self._shown_at_start: NDArray[np.float64] | None = None
        self._look_start_s = 0.0
        self._look_first_var_m2 = 0.0  # the believed variance at the look's first glance
        self._next_glance_s = 0.0
        self._last_amend_s = -np.inf
        self._homing_from_s = 0.0  # in-flight corrections start half-way through the primary
        self._moved_in_phase = False
        self._hand_at_start = calib_pos.copy()  # where the hand was when the movement began
        self.lag_s = self.p.familiar_lag_s
        """The display's lag as the operator has come to perceive it (s)."""
        self._look_s = 3 * self.traits.glance_s  # what a look costs, from experience
        self.regrasps = 0
        self.corrections_total = 0
        """Corrective submovements, in flight or after a look."""
        self.looks_total = 0

    @property
    def movement_start_s(self) -> float | None:
        """Start time (s) of the movement under way; None between movements."""
        return self._moves[0].start_s if self._moves else None

    # -- what the operator knows ---------------------------------------------------------------
    def criterion_m(self, t: float) -> float:
        """The current phase's criterion (m), loosened by the phase's effort so far."""
        if self.phase in _GRASP:
            c0 = self.task.grasp_clearance_m * self.traits.grasp_criterion_scale
        elif self.phase in _PLACE:
            c0 = self.traits.placement_criterion_m
        else:
            c0 = self.p.gross_criterion_m
        return c0 * self._loosening(t)

    def _loosening(self, t: float) -> float:
        """How much the criterion has grown with the effort spent correcting in this phase:
        from the arrival of its primary movement, which was planned to meet the criterion."""
        if self._correcting_from_s is None:
            return 1.0
        return 1.0 + (t - self._correcting_from_s) / self.traits.urgency_s

    def _goal_gripper(self, seen: Perceived, bowl_m: NDArray[np.float64]) -> NDArray[np.float64]:
        grasp = bowl_m + self.task.grasp_offset_m
        # Carrying, the operator puts the bowl it sees (or remembers) over the target it sees.
        place = seen.gripper_m + seen.target_m - bowl_m
        place[2] = seen.target_m[2] + self.task.grasp_offset_m[2] + 0.005
        up = np.array([0.0, 0.0, 1.0])
        lift_from = self._grasped_at if self._grasped_at is not None else grasp
        retract_from = self._released_at if self._released_at is not None else place
        return {
            Phase.REACH: grasp + up * self.p.approach_height_m,
            Phase.DESCEND: grasp,
            Phase.LIFT: lift_from + up * self.p.carry_height_m,
            Phase.TRANSPORT: place + up * self.p.carry_height_m,
            Phase.LOWER: place,
            # Straight up from where the hand let go, to clear the bowl.
            Phase.RETRACT: retract_from + up * self.p.approach_height_m,
            # Back to rest: the arm leaves the camera's view of the bowl for it to be tracked.
            Phase.HOME: self.task.rest_gripper_m,
        }[self.phase]

    def _judgement(self, seen: Perceived) -> tuple[NDArray[np.float64], str, bool]:
        """The covariance (m^2) of the current phase's error judgement, the axes it is judged
        on, and whether the display shows what the judgement relates (for homing in)."""
        if self.phase in _PLACE:
            cov = seen.placement_cov
            if seen.placed_by_gripper and self._memory.holding:
                cov = cov + self._memory.in_hand_cov
            visible = seen.bowl_m is not None or (seen.placed_by_gripper and seen.gripper_seen)
            return cov, "xy", visible and seen.gripper_seen
        return seen.grasp_cov, "xyz", seen.gripper_seen and seen.bowl_m is not None

    def _sure_within(self, t: float, error: NDArray[np.float64], seen: Perceived) -> float:
        """How sure the operator is that ``error`` (m) is within the phase's criterion. Placing,
        the criterion is in the table's plane; the height must first be reached, as any
        movement without a precision demand (within ``gross_criterion_m``)."""
        cov, axes, _ = self._judgement(seen)
        if axes == "xy" and abs(error[2]) > self.p.gross_criterion_m:
            return 0.0
        return probability_within(error, cov, self.criterion_m(t), axes)

    def _look_cost_s(self) -> float:
        """What one more look costs, as the operator has come to know it (s)."""
        p = self.p
        return p.arrival_window_s + self.lag_s + self._look_s + p.motor_delay_s

    # -- moving ----------------------------------------------------------------------------------
    def _hand_delta(self, gripper_delta_m: NDArray[np.float64]) -> NDArray[np.float64]:
        """The hand's step (m) that moves the gripper by ``gripper_delta_m`` (the mapping is
        affine, so the step is the same from anywhere)."""
        return self._to_hand(self._hand + gripper_delta_m) - self._to_hand(self._hand)

    def _move(self, t: float, hand_delta: NDArray[np.float64], start_s: float) -> None:
        """Add a submovement of the hand by ``hand_delta`` (m) from ``start_s`` (s), timed by the
        planner, its endpoint scattered by its speed."""
        amplitude = float(np.linalg.norm(hand_delta))
        criterion = self.criterion_m(t)
        duration = submovement_duration_s(
            amplitude, criterion, self._look_cost_s(), self.p.noise_k_s
        )
        duration = max(
            duration * self.traits.movement_time_factor,
            MIN_JERK_PEAK * amplitude / self.p.peak_speed_m_s,
            0.1,
        )
        sd = self.p.noise_floor_m + self.p.noise_k_s * amplitude / duration
        delta = hand_delta + self._rng.normal(0.0, sd, 3)
        self._moves.append(_Submovement(start_s, delta, duration))
        self._mode = _Mode.MOVE

    def _advance_hand(self, t: float) -> None:
        done = [m for m in self._moves if t >= m.start_s + m.duration_s]
        for m in done:
            self._base = self._base + m.delta_m
            self._moves.remove(m)
        self._hand = self._base + sum((m.done_at(t) for m in self._moves), np.zeros(3))

    def _hand_moved_since(self, since_s: float) -> NDArray[np.float64]:
        """How far the hand has moved since ``since_s`` (m), from its own recent path."""
        before = next((h for ts, h in reversed(self._hands) if ts <= since_s), None)
        if before is None:  # the lag reaches back before what it remembers: the oldest
            before = self._hands[0][1] if self._hands else self._hand
        return self._hand - before

    def _remaining_m(self, t: float) -> NDArray[np.float64]:
        """The hand's displacement still to come from the submovements under way (m)."""
        return sum((m.delta_m - m.done_at(t) for m in self._moves), np.zeros(3))

    # -- seeing ----------------------------------------------------------------------------------
    def _watch(self, view: DisplayFrame) -> None:
        """Keep the display's gripper over the arrival window; None where it is not shown."""
        # A prediction is of the operator's present, newer than the frame it is drawn over.
        predicted = view.shown_predicted
        stamp = view.time_s if predicted is None else predicted.time_s
        if self._shown and stamp <= self._shown[-1][0]:
            return
        cues = view.cues
        seen = cues.ghost or cues.predictive_ghost or view.gripper_in_camera
        self._shown.append((stamp, shown_gripper_m(view) if seen else None))
        while self._shown and self._shown[0][0] < stamp - 2 * self.p.arrival_window_s:
            self._shown.popleft()

    def _arrived(self, t: float, expected_m: float) -> bool:
        """The display has shown the gripper still over the window, after showing the movement
        the operator made (``expected_m``, how far the hand went; m)."""
        p = self.p
        if t - self._hand_stop_s > p.arrival_timeout_s:
            return True
        latest = self._shown[-1][0] if self._shown else -np.inf
        window = [s for ts, s in self._shown if ts >= latest - p.arrival_window_s]
        if not self._shown or any(s is None for s in window):
            # Not shown: the operator trusts its own arm, after the window and the lag it knows.
            return t - self._hand_stop_s >= p.arrival_window_s + self.lag_s
        if self._shown[0][0] > latest - p.arrival_window_s + 1e-9:
            return False  # not a whole window seen yet
        spread = max(float(np.linalg.norm(s - window[-1])) for s in window)
        if spread > p.arrival_speed_m_s * p.arrival_window_s:
            return False
        if self._shown_at_start is None or expected_m < 0.01:
            return t - self._hand_stop_s >= p.arrival_window_s
        shown_moved = float(np.linalg.norm(window[-1] - self._shown_at_start))
        return shown_moved >= 0.5 * expected_m

    def _glance(self, view: DisplayFrame) -> tuple[Perceived, NDArray[np.float64] | None]:
        seen = perceive(view, self.p.perception, self._errors, self.traits.depth_factor)
        return seen, self._memory.bowl_m(seen)

    # -- deciding --------------------------------------------------------------------------------
    def _start_look(self, t: float) -> None:
        self._mode = _Mode.LOOK
        self._errors.new_look()
        self._look_start_s = self._next_glance_s = t
        self.looks_total += 1

    def _look(self, t: float, view: DisplayFrame) -> None:
        """One glance of a look; decide once sure enough either way."""
        seen, bowl = self._glance(view)
        self._next_glance_s = t + self.traits.glance_s
        if bowl is None:  # never seen yet: keep looking
            return
        carrying = self.phase in (Phase.LIFT, Phase.TRANSPORT)
        if carrying and self.regrasps < self.p.max_regrasps and self._memory.left_behind(seen):
            self._regrasp(t, seen)
            return
        error = self._goal_gripper(seen, bowl) - seen.gripper_m
        sure = self._sure_within(t, error, seen)
        confidence = self.traits.confidence
        looked = t - self._look_start_s
        glances = round(looked / self.traits.glance_s) + 1
        variance = float(np.trace(self._judgement(seen)[0]))
        if glances == 1:
            self._look_first_var_m2 = variance
        saturated = averaging_saturated(self._look_first_var_m2, variance, glances)
        accept = sure >= confidence
        if not (accept or sure <= 1.0 - confidence or saturated or looked >= self.p.max_look_s):
            return  # not sure either way: look again
        self._look_s = 0.5 * self._look_s + 0.5 * (looked + self.traits.glance_s)
        if accept:
            self._advance(t)
        else:
            self._correct(t, seen, error)

    def _correct(self, t: float, seen: Perceived, error: NDArray[np.float64]) -> None:
        if self._moves or self.phase not in _MOVES:
            return
        if self._moved_in_phase:
            self.corrections_total += 1
        self._moved_in_phase = True
        self._move(t, self._hand_delta(error), t + self.p.motor_delay_s)
        primary = self._moves[-1]
        self._homing_from_s = primary.start_s + 0.5 * primary.duration_s
        self._shown_at_start = self._shown[-1][1] if self._shown else None
        self._hand_at_start = self._hand.copy()

    def _home_in(self, t: float, view: DisplayFrame) -> None:
        """A glance during a movement: correct in flight where the display shows the gripper
        and the goal and its lag is short."""
        p = self.p
        if (
            self.phase not in (*_GRASP, *_PLACE)
            or self.lag_s > p.move_and_wait_lag_s
            or t < self._next_glance_s
            # A correction's effect must be on the display before the next one is planned.
            or t < self._last_amend_s + p.visuomotor_delay_s + self.lag_s
            or t < self._homing_from_s
        ):
            return
        self._next_glance_s = t + self.traits.glance_s
        self._errors.new_look()
        seen, bowl = self._glance(view)
        _, _, visible = self._judgement(seen)
        if bowl is None or not visible:
            return
        # Where the gripper will end: as seen now, plus what the hand did over the lag the
        # operator believes the display has, plus what the hand has still to do. A lag longer
        # than it believes makes the prediction fall short, and the correction overshoot.
        predicted = seen.gripper_m + self._hand_moved_since(t - self.lag_s) + self._remaining_m(t)
        error = self._goal_gripper(seen, bowl) - predicted
        # As after a look, it corrects what it is sure will miss.
        if self._sure_within(t, error, seen) > 1 - self.traits.confidence:
            return
        self.corrections_total += 1
        self._last_amend_s = t
        self._move(t, self._hand_delta(error), t + p.motor_delay_s)

    def _regrasp(self, t: float, seen: Perceived) -> None:
        """The bowl stayed on the table: open the hand and reach for it again."""
        self.regrasps += 1
        self._memory.release()
        self._memory.bowl_m(seen)  # where it was seen just now
        self._grip = 0.0
        self._grasped_at = None
        self._enter(Phase.REACH, t)
        self._mode = _Mode.WAIT
        self._wait_until = t + self.p.grip_ramp_s

    def _enter(self, phase: Phase, t: float) -> None:
        self.phase = phase
        self._correcting_from_s = None
        self._moved_in_phase = False

    def _advance(self, t: float) -> None:
        self._enter(self._phases[self._phases.index(self.phase) + 1], t)
        self._mode = _Mode.WAIT
        ramp = self.phase in (Phase.CLOSE, Phase.OPEN)
        self._wait_until = t + (self.p.grip_ramp_s if ramp else self.p.motor_delay_s)

    # -- acting ----------------------------------------------------------------------------------
    def step(self, time_s: float, view: DisplayFrame) -> OperatorOutput:
        """The hand's pose and the grip at ``time_s`` (s), the sample's own time.

        ``view`` is the newest display content that has reached the operator, which is older
        than ``time_s`` by the camera period and the return link's delay: it informs the
        operator's decisions, never the time at which the hand is evaluated.
        """
        t = time_s
        self._watch(view)
        self._hands.append((t, self._hand.copy()))
        while self._hands[0][0] < t - 2.0:
            self._hands.popleft()
        if self._mode is _Mode.MOVE:
            self._advance_hand(t)
            if self._moves:
                if self.phase in _MOVES:
                    self._home_in(t, view)
            else:
                self._hand_stop_s = t
                self._mode = _Mode.WATCH
        elif self._mode is _Mode.WATCH:
            if self.phase not in _MOVES:
                self._decide(t, view)
            elif self._arrived(t, float(np.linalg.norm(self._hand - self._hand_at_start))):
                lag = t - self._hand_stop_s - self.p.arrival_window_s
                self.lag_s = 0.5 * self.lag_s + 0.5 * max(lag, 0.0)
                if self._correcting_from_s is None:
                    self._correcting_from_s = t
                self._start_look(t)
        elif self._mode is _Mode.LOOK:
            if t >= self._next_glance_s:
                self._look(t, view)
        elif t >= self._wait_until:
            self._decide(t, view)
        return self._output(t)

    def _decide(self, t: float, view: DisplayFrame) -> None:
        if self.phase is Phase.CALIBRATE:
            self._enter(Phase.ALIGN, t)
            self._align(t)
        elif self.phase is Phase.ALIGN:
            self._enter(Phase.ENGAGE, t)
            self._mode = _Mode.WAIT
            self._wait_until = t + 0.5
        elif self.phase is Phase.ENGAGE:
            if view.engaged:
                self._enter(Phase.REACH, t)
                self._start_look(t)
            else:  # the indicator stays off: align the hand again, from memory of the pose
                self._enter(Phase.ALIGN, t)
                self._align(t)
        elif self.phase in (Phase.CLOSE, Phase.OPEN):
            closing = self.phase is Phase.CLOSE
            self._grip = 1.0 if closing else 0.0
            self._errors.new_look()
            seen, bowl = self._glance(view)
            if closing:
                self._grasped_at = seen.gripper_m
                self._memory.grasp(seen, bowl)
            else:
                self._released_at = seen.gripper_m
                self._memory.release()
            wait = self.p.grasp_wait_known_s if seen.closure_known else self.p.grasp_wait_unknown_s
            self._advance(t)
            self._wait_until = t + wait
        elif self.phase in _MOVES:
            self._start_look(t)

    def _align(self, t: float) -> None:
        """Bring the hand to where it commands the resting gripper, from memory of the pose."""
        self._move(t, self._to_hand(self.task.rest_gripper_m) - self._hand, t)
        self._shown_at_start, self._hand_at_start = None, self._hand.copy()

    def _output(self, t: float) -> OperatorOutput:
        w = 2 * np.pi * np.asarray(self.p.tremor_hz)
        tremor = (
            self.p.tremor_amplitude_m * np.sin(w[:, None] * t + self._tremor_phase).sum(axis=0) / 2
        )
        if self.phase is Phase.CALIBRATE:
            rot = self._rot_path(0.0).as_matrix()
            tremor = np.zeros(3)  # the posture is held against a support during calibration
        elif self.phase is Phase.ALIGN and self._moves:
            m = self._moves[0]
            rot = self._rot_path(float(minimum_jerk_profile((t - m.start_s) / m.duration_s)))
            rot = rot.as_matrix()
        else:
            rot = self._work_R
        grip = self._grip
        if self.phase in (Phase.CLOSE, Phase.OPEN):
            target = 1.0 if self.phase is Phase.CLOSE else 0.0
            grip = self._grip + (target - self._grip) * min(
                1.0, (t - (self._wait_until - self.p.grip_ramp_s)) / self.p.grip_ramp_s
            )
        return OperatorOutput(
            t, self._hand + tremor, rot, float(np.clip(grip, 0.0, 1.0)), self.phase
        )

"""A synthetic operator who does the pick-and-place through the teleoperation system.

It is a model of a person, not a replayed path: each movement is a minimum-jerk segment whose
duration follows Fitts's law, planned from what the operator perceives on the display
(:mod:`arteleop.operator.perception`), with signal-dependent endpoint noise, physiological tremor,
and corrective sub-movements while the perceived error exceeds the movement's tolerance. AR
changes its performance only through what it can perceive. Its output is a hand pose in the torso
frame and a grip value; the loop turns them into IMU signals through the arm model.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from enum import Enum

import numpy as np
from numpy.typing import NDArray
from scipy.spatial.transform import Rotation, Slerp

from arteleop.ar_features import DisplayFrame
from arteleop.errors import ConfigurationError
from arteleop.operator.arm_model import ArmModel, hand_pose, segment_rotations
from arteleop.operator.minimum_jerk import minimum_jerk_profile
from arteleop.operator.perception import (
    BowlMemory,
    Perceived,
    PerceptionParams,
    PerceptualNoise,
    perceive,
)
from arteleop.operator.recording import CalibrationPosture


@dataclass(frozen=True)
class OperatorParams:
    """Every parameter of the synthetic operator, with its source or reasoning.

    Attributes:
        fitts_a_s: Fitts intercept (s). Direct pointing has 0.1-0.2 s (MacKenzie, HCI 1992);
            teleoperation through an HMD with ~0.1 s latency roughly doubles it.
        fitts_b_s_per_bit: Fitts slope (s/bit), Shannon form MT = a + b log2(D/W + 1). Direct
            pointing 0.1-0.2 s/bit; remote manipulation with delayed visual feedback 0.3-0.6
            (Sheridan & Ferrell 1963; Hoffmann 1992).
        dwell_s: Pause after each movement to look at the result (visual reaction, ~0.25 s).
        settle_speed_m_s: Under delay, people move and wait (Sheridan & Ferrell 1963): the
            result is judged only once the displayed gripper moves slower than this.
        endpoint_noise_ratio: Endpoint SD per metre moved, signal-dependent noise (Harris &
            Wolpert, Nature 1998): a few percent of the amplitude.
        tremor_amplitude_m: Physiological tremor, per axis, below a millimetre.
        tremor_hz: Its two frequency components, in the 8-12 Hz band.
        max_corrections: Corrective sub-movements per phase before carrying on regardless.
        discrimination_sd: A perceived error below this many standard deviations of its own
            judgement (``Perceived.grasp_sd_m``, ``placement_sd_m``) is not corrected, however
            strict the movement's tolerance: the operator cannot tell it from no error. 1 is
            the conventional discrimination threshold (d' = 1, Green & Swets 1966).
        max_regrasps: Times the operator goes back for a bowl that a missed grasp left behind,
            seen on the table while lifting or carrying.
        grip_ramp_s: Time to squeeze or release the pinch sensor.
        grasp_wait_known_s: Wait after closing when the closure is visible (grip bar or gripper).
        grasp_wait_unknown_s: Wait when it is not: the operator must infer it.
        approach_height_m: Height above the grasp or place point to approach from.
        carry_height_m: Height of the bowl's transport above the table.
        expertise_speedup: Fitts slope factor for an expert (>= 2 h/week of AR/VR or games).
        expertise_noise: Endpoint-noise factor for an expert.
        hand_pitch_rad: Pitch of the hand (about torso y) while working: knuckles slightly down.
        perception: Perception error model.
    """

    fitts_a_s: float = 0.3
    fitts_b_s_per_bit: float = 0.3
    dwell_s: float = 0.25
    settle_speed_m_s: float = 0.02
    endpoint_noise_ratio: float = 0.03
    tremor_amplitude_m: float = 0.0003
    tremor_hz: tuple[float, float] = (9.0, 11.0)
    max_corrections: int = 4
    discrimination_sd: float = 1.0
    max_regrasps: int = 2
    grip_ramp_s: float = 0.3
    grasp_wait_known_s: float = 0.4
    grasp_wait_unknown_s: float = 1.0
    approach_height_m: float = 0.10
    carry_height_m: float = 0.15
    expertise_speedup: float = 0.8
    expertise_noise: float = 0.8
    hand_pitch_rad: float = 0.4
    perception: PerceptionParams = field(default_factory=PerceptionParams)

    def __post_init__(self) -> None:
        if self.fitts_b_s_per_bit <= 0 or self.fitts_a_s < 0 or self.max_corrections < 0:
            raise ConfigurationError("OperatorParams: Fitts a >= 0, b > 0 and max_corrections >= 0")


@dataclass(frozen=True)
class Expertise:
    """Weekly hours bucket (1: < 1 h, 2: 2-5 h, 3: > 5 h) for AR/VR and for video games."""

    avr_hours: int = 1
    games_hours: int = 1

    @property
    def expert(self) -> bool:
        return max(self.avr_hours, self.games_hours) >= 2


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


# Required precision (m) of each movement: Fitts's W.
_TOLERANCE = {
    Phase.REACH: 0.02, Phase.DESCEND: 0.006, Phase.LIFT: 0.05,
    Phase.TRANSPORT: 0.02, Phase.LOWER: 0.006, Phase.RETRACT: 0.05, Phase.HOME: 0.05,
}  # fmt: skip


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
    """

    grasp_offset_m: NDArray[np.float64]
    rest_gripper_m: NDArray[np.float64]


def hand_from_calibration(
    arm: ArmModel, calibration: CalibrationPosture, hand_pitch_rad: float
) -> tuple[NDArray[np.float64], Slerp]:
    """The hand's position in the calibration posture (torso frame, m), and the path of its
    rotation from that posture (0) to the working one, pitched ``hand_pitch_rad`` about the
    torso's y (1)."""
    position, R_hand = hand_pose(arm, segment_rotations(calibration.angles))
    path = [Rotation.from_matrix(R_hand), Rotation.from_euler("y", hand_pitch_rad)]
    return position, Slerp([0.0, 1.0], Rotation.concatenate(path))


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
        expertise: Expertise | None = None,
    ) -> None:
        """``hand_for_gripper(p)`` maps a gripper position to the hand position that commands it."""
        self.p = params or OperatorParams()
        self.task = task
        self._to_hand = hand_for_gripper
        self._rng = rng
        expert = (expertise or Expertise()).expert
        self._b = self.p.fitts_b_s_per_bit * (self.p.expertise_speedup if expert else 1.0)
        self._noise = self.p.expertise_noise if expert else 1.0
        self._calib = calibration
        calib_pos, self._rot_path = hand_from_calibration(arm, calibration, self.p.hand_pitch_rad)
        self._work_R = Rotation.from_euler("y", self.p.hand_pitch_rad).as_matrix()
        self._phases = list(Phase)
        self.phase = Phase.CALIBRATE
        self._hand = calib_pos.copy()
        self._grip = 0.0
        self._seg: tuple[float, NDArray[np.float64], NDArray[np.float64], float] | None = None
        self._wait_until = calibration.hold_s + 0.2
        self._corrections = 0
        self.corrections_total = 0
        self._tremor_phase = rng.uniform(0, 2 * np.pi, (2, 3))
        self._grasped_at: NDArray[np.float64] | None = None
        self._released_at: NDArray[np.float64] | None = None
        self._bowl_memory = BowlMemory()
        self._perceptual_noise = PerceptualNoise(rng, self.p.perception.persistence_s)
        self.regrasps = 0
        self._previous_view: DisplayFrame | None = None  # the display's last two contents
        self._last_view: DisplayFrame | None = None

    @property
    def movement_start_s(self) -> float | None:
        """Start time (s) of the movement under way; None between movements."""
        return None if self._seg is None else self._seg[0]

    # -- planning -------------------------------------------------------------------------------
    def _fitts_s(self, distance_m: float, width_m: float) -> float:
        return self.p.fitts_a_s + self._b * np.log2(distance_m / width_m + 1.0)

    def _start_segment(self, t: float, hand_goal: NDArray[np.float64], width_m: float) -> None:
        d = float(np.linalg.norm(hand_goal - self._hand))
        noise = self.p.endpoint_noise_ratio * self._noise * d
        goal = hand_goal + self._rng.normal(0.0, noise / np.sqrt(3), 3)
        self._seg = (t, self._hand.copy(), goal, self._fitts_s(max(d, 1e-3), width_m))

    def _look(self, view: DisplayFrame) -> tuple[Perceived, NDArray[np.float64] | None]:
        """One look at the display: the estimates, and the bowl as seen or remembered (None
        before it was ever seen)."""
        seen = perceive(view, self.p.perception, self._perceptual_noise, self._noise)
        return seen, self._bowl_memory.bowl_m(seen)

    def _goal_gripper(
        self, phase: Phase, seen: Perceived, bowl_m: NDArray[np.float64]
    ) -> NDArray[np.float64]:
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
        }[phase]

    def _plan(self, t: float, view: DisplayFrame) -> None:
        """Look at the display and plan the phase's (next) movement, or move on."""
        last, previous = self._last_view, self._previous_view
        if last is not None and previous is not None:
            moved = np.linalg.norm(last.gripper_m - previous.gripper_m)
            if moved / (last.time_s - previous.time_s) > self.p.settle_speed_m_s:
                self._wait_until = t + 0.05  # the arm is still catching up: look again shortly
                return
        seen, bowl = self._look(view)
        if bowl is None:  # never seen yet: look again shortly
            self._wait_until = t + 0.1
            return
        carrying = self.phase in (Phase.LIFT, Phase.TRANSPORT)
        if carrying and self.regrasps < self.p.max_regrasps and self._bowl_memory.left_behind(seen):
            self._regrasp(t, seen)
            return
        goal = self._goal_gripper(self.phase, seen, bowl)
        error = goal - seen.gripper_m
        width = _TOLERANCE[self.phase]
        if (
            np.linalg.norm(error) <= max(width / 2, self._discernible_m(seen))
            or self._corrections > self.p.max_corrections
        ):
            self._advance(t)
            return
        if self._corrections > 0:
            self.corrections_total += 1
        self._corrections += 1
        # Move the hand by the perceived gripper error, mapped into the hand's space.
        hand_goal = self._hand + (
            self._to_hand(seen.gripper_m + error) - self._to_hand(seen.gripper_m)
        )
        self._start_segment(t, hand_goal, width)

    def _discernible_m(self, seen: Perceived) -> float:
        """The smallest error (m) the operator can tell from none in the current phase."""
        if self.phase in (Phase.REACH, Phase.DESCEND):
            return self.p.discrimination_sd * seen.grasp_sd_m
        if self.phase in (Phase.TRANSPORT, Phase.LOWER):
            return self.p.discrimination_sd * seen.placement_sd_m
        return 0.0

    def _regrasp(self, t: float, seen: Perceived) -> None:
        """The bowl stayed on the table: open the hand and reach for it again."""
        self.regrasps += 1
        self._bowl_memory.release()
        self._bowl_memory.bowl_m(seen)  # where it was seen just now
        self._grip = 0.0
        self._grasped_at = None
        self.phase = Phase.REACH
        self._corrections = 0
        self._seg = None
        self._wait_until = t + self.p.grip_ramp_s

    def _advance(self, t: float) -> None:
        self.phase = self._phases[self._phases.index(self.phase) + 1]
        self._corrections = 0
        self._seg = None
        if self.phase in (Phase.CLOSE, Phase.OPEN):
            self._wait_until = t + self.p.grip_ramp_s

    # -- acting ---------------------------------------------------------------------------------
    def step(self, time_s: float, view: DisplayFrame) -> OperatorOutput:
        """The hand's pose and the grip at ``time_s`` (s), the sample's own time.

        ``view`` is the newest display content that has reached the operator, which is older
        than ``time_s`` by the camera period and the return link's delay: it informs the
        operator's decisions, never the time at which the hand is evaluated.
        """
        t = time_s
        if self._seg is not None:
            t0, a, b, dur = self._seg
            s = minimum_jerk_profile((t - t0) / dur)
            self._hand = a + s * (b - a)
            if t - t0 >= dur + self.p.dwell_s:
                self._seg = None
        elif t >= self._wait_until:
            self._decide(t, view)
        if self._last_view is None or view.time_s > self._last_view.time_s:
            self._previous_view, self._last_view = self._last_view, view
        return self._output(t)

    def _decide(self, t: float, view: DisplayFrame) -> None:
        if self.phase is Phase.CALIBRATE:
            self.phase = Phase.ALIGN
            self._start_segment(t, self._to_hand(self.task.rest_gripper_m), 0.02)
        elif self.phase is Phase.ALIGN:
            self.phase = Phase.ENGAGE
            self._wait_until = t + 0.5
        elif self.phase is Phase.ENGAGE:
            if view.engaged:
                self.phase = Phase.REACH
                self._plan(t, view)
            else:  # the indicator stays off: align the hand again, from memory of the pose
                self.phase = Phase.ALIGN
                self._start_segment(t, self._to_hand(self.task.rest_gripper_m), 0.02)
        elif self.phase in (Phase.CLOSE, Phase.OPEN):
            closing = self.phase is Phase.CLOSE
            self._grip = 1.0 if closing else 0.0
            seen, bowl = self._look(view)
            if closing:
                self._grasped_at = seen.gripper_m
                self._bowl_memory.grasp(seen, bowl)
            else:
                self._released_at = seen.gripper_m
                self._bowl_memory.release()
            wait = self.p.grasp_wait_known_s if seen.closure_known else self.p.grasp_wait_unknown_s
            self._advance(t)
            self._wait_until = t + wait
        elif self.phase is not Phase.DONE:
            self._plan(t, view)

    def _output(self, t: float) -> OperatorOutput:
        w = 2 * np.pi * np.asarray(self.p.tremor_hz)
        tremor = (
            self.p.tremor_amplitude_m * np.sin(w[:, None] * t + self._tremor_phase).sum(axis=0) / 2
        )
        if self.phase is Phase.CALIBRATE:
            rot = self._rot_path(0.0).as_matrix()
            tremor = np.zeros(3)  # the posture is held against a support during calibration
        elif self.phase is Phase.ALIGN and self._seg is not None:
            t0, _, _, dur = self._seg
            rot = self._rot_path(float(minimum_jerk_profile((t - t0) / dur))).as_matrix()
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

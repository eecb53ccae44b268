"""The synthetic operator's constants: the same for every person and every task."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from arteleop.checks import Bounds, check_fields
from arteleop.operator.simulated.own_errors import SeenOutcomes
from arteleop.operator.simulated.perception import PerceptionParams
from arteleop.operator.simulated.scatter import MovementScatter


@dataclass(frozen=True)
class OperatorParams:
    """The synthetic operator's constants, the same for every person
    (docs/explanation/operator-model.md gives each one's value and source).

    Attributes:
        scatter: Where a submovement's endpoint scatters, along its way and across it.
        peak_speed_m_s: Fastest peak speed of the hand (m/s): the arm's, a physical cap on
            the speed the planner chooses.
        tremor_amplitude_m: Physiological tremor per axis (m).
        tremor_hz: Its two components (Hz).
        motor_delay_s: From a decision to the start of the movement (s).
        visuomotor_delay_s: From a glance during a movement to the correction it starts (s).
        arrival_window_s: The display must show the gripper still this long (s)...
        arrival_speed_m_s: ...moving at most this fast (m/s), for it to have arrived.
        arrival_timeout_s: After the hand stops, the operator looks anyway after this (s).
        familiar_lag_s: The display's lag the operator knows from practice on the system
            (s): its first estimate of the lag, before a trial shows it another.
        seen_outcomes: The outcomes of its earlier trials the operator has seen (none, for
            its first): how often it missed tells it how far to trust its judgement.
        own_error_prior_sd: SD of the operator's prior on the log of the factor its
            judgement's covariance falls short by, half-normal about 0
            (:mod:`arteleop.operator.simulated.own_errors`).
        lag_learning_rate: How much of the difference between a movement's observed lag and
            the believed one the belief takes on (per movement): adapting to a delay is slow.
        timing_weber: The SD of a timed interval as a share of its mean (scalar timing): the
            wait for the display, and the lag a prediction in flight reaches back over.
        motion_threshold_m: The smallest displacement of the shown gripper the operator sees
            as a movement (m); movements under twice it teach no lag.
        gross_criterion_m: Criterion of the movements without a precision demand (in the
            pick-and-place: lift, retract, home; m).
        max_look_s: A look ends by then, sure or not (s).
        grip_ramp_s: Time to squeeze or release the pinch sensor (s).
        grip_wait_known_s: Wait after squeezing or releasing when the display shows the
            gripper's closure (s).
        grip_wait_unknown_s: Wait when it does not: the operator must infer it (s).
        hand_pitch_rad: Pitch of the hand (about torso y) while working (rad).
        perception: Perception's constants.
    """

    scatter: MovementScatter = field(default_factory=MovementScatter)
    peak_speed_m_s: float = 0.5
    tremor_amplitude_m: float = 0.0003
    tremor_hz: tuple[float, float] = (9.0, 11.0)
    motor_delay_s: float = 0.07
    visuomotor_delay_s: float = 0.12
    arrival_window_s: float = 0.25
    arrival_speed_m_s: float = 0.02
    arrival_timeout_s: float = 3.0
    familiar_lag_s: float = 0.245
    seen_outcomes: SeenOutcomes = field(default_factory=SeenOutcomes)
    own_error_prior_sd: float = 0.69
    lag_learning_rate: float = 0.03
    timing_weber: float = 0.15
    motion_threshold_m: float = 0.005
    gross_criterion_m: float = 0.05
    max_look_s: float = 1.5
    grip_ramp_s: float = 0.3
    grip_wait_known_s: float = 0.4
    grip_wait_unknown_s: float = 1.0
    hand_pitch_rad: float = 0.4
    perception: PerceptionParams = field(default_factory=PerceptionParams)

    def __post_init__(self) -> None:
        positive, non_negative = Bounds(0, above=True), Bounds(0)
        check_fields(self, {
            **dict.fromkeys(("peak_speed_m_s", "arrival_window_s",
                             "arrival_speed_m_s", "arrival_timeout_s", "gross_criterion_m",
                             "max_look_s", "grip_ramp_s", "own_error_prior_sd"), positive),
            **dict.fromkeys(("motor_delay_s", "visuomotor_delay_s", "familiar_lag_s",
                             "tremor_amplitude_m", "grip_wait_known_s",
                             "grip_wait_unknown_s"), non_negative),
            "hand_pitch_rad": Bounds(-math.pi / 2, math.pi / 2,
                                     text="-1.571 to 1.571 (rad: a quarter turn either way)"),
            "lag_learning_rate": Bounds(0, 1, "a share"),
            "timing_weber": Bounds(0, 1, "a share of the wait"),
            "motion_threshold_m": Bounds(0, above=True),
        })  # fmt: skip

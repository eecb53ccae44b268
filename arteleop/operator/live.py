"""A live operator without IMUs: a hand target and a grip value set by hand, e.g. in the GUI.

The person drags the gripper's target; the operator here holds the calibration posture, brings
the hand to the target's hand position (so that the controller engages) and then follows it.
Its output goes through the simulated wearable, reconstruction, mapping, IK and trajectory like
a worn one's, so the robot responds as it would to a person wearing the IMUs.
"""

from __future__ import annotations

import threading
from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike, NDArray

from arteleop.ar_features import DisplayFrame
from arteleop.operator.minimum_jerk import minimum_jerk_profile
from arteleop.operator.output import ALIGN, CALIBRATE, OperatorOutput
from arteleop.operator.wearable.arm_model import ArmModel
from arteleop.operator.wearable.posture import CalibrationPosture, hand_from_calibration

ALIGN_S = 1.5
"""Time to bring the hand from the calibration posture to the target (s)."""
FOLLOW_TIME_CONSTANT_S = 0.15
"""The hand follows the target with this lag (s): a drag in the browser jumps, a hand does not."""
FOLLOW = "follow"
"""The live operator's phase once its hand follows the target."""


class HandTarget:
    """The gripper's target position (base frame, m) and the grip (0 open .. 1 closed), set from
    any thread (a GUI callback) and read by the loop."""

    def __init__(self, gripper_m: ArrayLike, grip: float = 0.0) -> None:
        self._lock = threading.Lock()
        self._gripper_m = np.array(gripper_m, dtype=np.float64)
        self._grip = float(grip)

    def set(self, gripper_m: ArrayLike | None = None, grip: float | None = None) -> None:
        with self._lock:
            if gripper_m is not None:
                self._gripper_m = np.array(gripper_m, dtype=np.float64)
            if grip is not None:
                self._grip = float(np.clip(grip, 0.0, 1.0))

    def get(self) -> tuple[NDArray[np.float64], float]:
        with self._lock:
            return self._gripper_m.copy(), self._grip


class LiveOperator:
    """Turns a :class:`HandTarget` into the operator's hand; call :meth:`step` at the wearable's
    rate, like :class:`~arteleop.operator.SyntheticOperator`."""

    def __init__(
        self,
        target: HandTarget,
        hand_for_gripper: Callable[[NDArray[np.float64]], NDArray[np.float64]],
        arm: ArmModel,
        calibration: CalibrationPosture,
        hand_pitch_rad: float = 0.4,
    ) -> None:
        self.target = target
        self._to_hand = hand_for_gripper
        self._calibration = calibration
        calib_pos, self._rot_path = hand_from_calibration(arm, calibration, hand_pitch_rad)
        self._hand = calib_pos
        self._from = calib_pos
        # Where the hand aligns: on the gripper at rest, where the target is as the trial
        # begins. A target moved meanwhile (a key pressed with Start) is followed once the
        # robot has engaged: aligned on it instead, the hand was not on the gripper, and the
        # robot never engaged until the person moved the target back.
        self._rest_goal = hand_for_gripper(target.get()[0])
        self._last_t: float | None = None
        self.phase = CALIBRATE

    def step(self, time_s: float, view: DisplayFrame) -> OperatorOutput:
        """The hand at ``time_s`` (s): held for the calibration, aligned on the gripper at rest
        until ``view`` shows the robot engaged, then following the target (the person looks
        for themselves)."""
        gripper_m, grip = self.target.get()
        goal = self._to_hand(gripper_m)
        hold_s = self._calibration.hold_s
        if time_s < hold_s:
            self.phase = CALIBRATE
            return OperatorOutput(
                time_s, self._hand.copy(), self._rot_path(0.0).as_matrix(), 0.0, self.phase
            )
        s = (time_s - hold_s) / ALIGN_S
        if s < 1.0 or not view.engaged:  # on the gripper until the display says engaged
            self.phase = ALIGN
            k = float(minimum_jerk_profile(min(s, 1.0)))
            self._hand = self._from + k * (self._rest_goal - self._from)
            rotation = self._rot_path(k).as_matrix()
        else:
            self.phase = FOLLOW
            dt = 0.0 if self._last_t is None else time_s - self._last_t
            follow = 1.0 - np.exp(-dt / FOLLOW_TIME_CONSTANT_S)
            self._hand = self._hand + (goal - self._hand) * follow
            rotation = self._rot_path(1.0).as_matrix()
        self._last_t = time_s
        return OperatorOutput(time_s, self._hand.copy(), rotation, grip, self.phase)

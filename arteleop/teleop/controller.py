"""The robot side of the loop: from received wearable samples to arm and gripper commands.

States: CALIBRATING (collect the operator's initial posture hold), WAITING (calibrated; the arm
holds still until the operator's hand maps onto the gripper's current position, so engaging never
makes the arm jump) and ENGAGED (mapping -> IK -> trajectory -> position control at every tick).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from enum import Enum
from pathlib import Path
from typing import Protocol

import numpy as np
from numpy.typing import ArrayLike, NDArray

from arteleop.operator import ArmModel, CalibrationPosture
from arteleop.robot import WORK_POSTURE, ArmCommand, JointLimits
from arteleop.robot.grip_control import GripCommand, GripHysteresis
from arteleop.robot.ik import ArmIK, IKConfig, IKResult
from arteleop.robot.mapping import HandToGripper, MappingConfig
from arteleop.robot.trajectory import JointTrajectory, TrajectoryLimits
from arteleop.scene import Box
from arteleop.teleop.clock import LoopRates
from arteleop.teleop.hand_filter import HandFilter, HandFilterConfig
from arteleop.teleop.hand_speed import HandSpeed
from arteleop.teleop.reconstruction import HandSample, SampleStatus, StreamingReconstructor
from arteleop.teleop.sensor_calibration import calibrate_from_hold
from arteleop.teleop.timing import StageTimer


class OperatorBody(Protocol):
    """What the robot side knows of the operator's body: the arm model and the posture held
    to calibrate the wearable (an operator source provides both)."""

    arm: ArmModel
    calibration: CalibrationPosture


class ArmReading(Protocol):
    """What a control tick reads of the arm: its encoders and where they put the gripper (a
    :class:`~arteleop.scene.SiteState` at the site; a display frame on the operator's side)."""

    @property
    def arm_q_rad(self) -> NDArray[np.float64]: ...

    @property
    def gripper_m(self) -> NDArray[np.float64]: ...


class ControllerState(Enum):
    CALIBRATING = "calibrating"
    WAITING = "waiting"
    ENGAGED = "engaged"


@dataclass(frozen=True)
class ControllerConfig:
    """Robot-side settings.

    Attributes:
        mapping: Hand-to-gripper mapping.
        ik: IK weights and limits.
        grip: Grip hysteresis.
        engage_distance_m: Engage when the hand maps within this distance of the gripper...
        engage_speed_m_s: ...and the hand moves slower than this.
        speed_window_s: Window of the hand-speed estimate (see :class:`HandSpeed`).
        max_gap_s: Missing samples repeat the last pose up to this long; then the arm holds.
        hand_filter: The 1€ filter between the reconstructed hand and the mapping (the hand
            that is recorded and whose speed is measured is the reconstructed one, unfiltered).
    """

    mapping: MappingConfig = field(default_factory=MappingConfig)
    ik: IKConfig = field(default_factory=IKConfig)
    grip: GripHysteresis = field(default_factory=GripHysteresis)
    engage_distance_m: float = 0.05
    engage_speed_m_s: float = 0.05
    speed_window_s: float = 0.3
    max_gap_s: float = 0.1
    hand_filter: HandFilterConfig = field(default_factory=HandFilterConfig)


class TeleopController:
    """Turns wearable samples into arm commands for one trial.

    It is built from plain data (the URDF for the IK's model, the arm's joint limits, the table's
    box) and never holds the site: each control tick reads the arm's encoders from a
    :class:`~arteleop.scene.SiteState` and returns an :class:`~arteleop.robot.ArmCommand` for
    the loop to apply.
    """

    def __init__(
        self,
        urdf_path: Path,
        limits: JointLimits,
        q0_rad: ArrayLike,
        operator: OperatorBody,
        rates: LoopRates,
        table: Box | None = None,
        config: ControllerConfig | None = None,
        timer: StageTimer | None = None,
    ) -> None:
        """
        Args:
            urdf_path: Baxter's URDF, for the IK's model of the right arm.
            limits: The right arm's joint limits, in ``RIGHT_ARM_JOINTS`` order.
            q0_rad: (7,) the arm's joint positions when the trial starts (rad).
            operator: The operator's arm model and calibration posture, for reconstruction.
            rates: Control rate (IK ticks) and physics rate (trajectory steps).
            table: The table's box, kept clear of the forearm and gripper by the IK.
            config: Robot-side settings.
            timer: Times the ``mapping`` and ``ik`` stages of each control tick.
        """
        self.config = c = config or ControllerConfig()
        self.timer = timer or StageTimer()
        self.arm, self.posture = operator.arm, operator.calibration
        self.dt = 1.0 / rates.control_hz
        self._limits = limits
        q0 = np.asarray(q0_rad, dtype=np.float64)
        box = (None, None) if table is None else (table.center_m, table.half_extents_m)
        self.ik = ArmIK(urdf_path, limits, WORK_POSTURE, *box, c.ik)
        self.trajectory = JointTrajectory(
            TrajectoryLimits.from_joint_limits(limits), 1.0 / rates.physics_hz, q0
        )
        self.mapping = HandToGripper(c.mapping)
        self.grip = GripCommand(c.grip)
        self.state = ControllerState.CALIBRATING
        self._hold: list[NDArray[np.float64]] = []
        self._t0: float | None = None
        self.reconstructor: StreamingReconstructor | None = None
        self.last_hand: HandSample | None = None
        """The newest reconstructed hand, as the wearable measured it."""
        self.command_hand: HandSample | None = None
        """The newest hand as the mapping takes it: :attr:`last_hand` through the filter."""
        self._filter = HandFilter(c.hand_filter, rates.control_hz)
        self._speed = HandSpeed(c.speed_window_s)
        self.last_ik: IKResult | None = None
        self.last_target_m: NDArray[np.float64] | None = None
        """Where the mapping last put the gripper (base frame, m); None before calibration."""
        self.applied_sample_time_s = -np.inf  # newest operator sample acting on the arm
        self.unreachable_ticks = 0

    def receive(
        self, sample_time_s: float, sensor_quat_wxyz: NDArray[np.float64] | None, grip: float
    ) -> None:
        """A wearable sample arrived (``None`` quaternions: the sample was lost or invalid)."""
        if self.reconstructor is None:
            if self._t0 is None:
                self._t0 = sample_time_s
            if sensor_quat_wxyz is not None and np.isfinite(sensor_quat_wxyz).all():
                self._hold.append(np.asarray(sensor_quat_wxyz))
            if sample_time_s - self._t0 >= self.posture.hold_s:
                mounting = calibrate_from_hold(np.array(self._hold), self.posture)
                self.reconstructor = StreamingReconstructor(
                    self.arm, mounting, self.config.max_gap_s
                )
                self.state = ControllerState.WAITING
            return
        hand = self.reconstructor.update(sample_time_s, sensor_quat_wxyz, grip)
        if hand is None or hand.status is SampleStatus.LOST:
            return
        if self.last_hand is None or hand.time_s > self.last_hand.time_s:
            self._speed.update(hand.time_s, hand.hand_m)
            position, quat = self._filter(hand.time_s, hand.hand_m, hand.hand_quat_wxyz)
            self.command_hand = replace(hand, hand_m=position, hand_quat_wxyz=quat)
        self.last_hand = hand

    @property
    def hand_speed_m_s(self) -> float:
        """The operator's hand speed (m/s) over the last ``speed_window_s``."""
        return self._speed.speed_m_s

    @property
    def engaged(self) -> bool:
        """The arm follows the operator's hand."""
        return self.state is ControllerState.ENGAGED

    def control_tick(self, state: ArmReading) -> ArmCommand | None:
        """Mapping, IK and a new trajectory target from the newest hand sample; returns the
        gripper command once engaged (the arm's joint targets come from :meth:`physics_tick`).

        ``state`` gives the arm's encoders and the gripper's pose (``GRIPPER_FRAME`` observed),
        which engagement compares with the hand's mapped position.
        """
        hand = self.command_hand
        if hand is None or self.state is ControllerState.CALIBRATING:
            return None
        with self.timer.stage("mapping"):
            target = self.mapping.gripper_target(hand.hand_m, hand.hand_quat_wxyz)
        self.last_target_m = target[:3, 3]
        if self.state is ControllerState.WAITING:
            offset_m = np.linalg.norm(target[:3, 3] - state.gripper_m)
            aligned = offset_m < self.config.engage_distance_m
            if not (aligned and self.hand_speed_m_s < self.config.engage_speed_m_s):
                return None
            self.ik.reset(state.arm_q_rad)
            self.trajectory.reset(state.arm_q_rad)
            self.state = ControllerState.ENGAGED
        with self.timer.stage("ik"):
            self.ik.set_target(target)
            result = self.ik.step(self.dt)
        self.last_ik = result
        self.unreachable_ticks += not result.reachable
        self.trajectory.set_target(result.q_rad)
        self.applied_sample_time_s = hand.time_s
        return ArmCommand(gripper_closure=self.grip.update(hand.grip))

    def physics_tick(self) -> ArmCommand | None:
        """One trajectory step: the arm's joint targets for the next physics step, once engaged."""
        if self.state is not ControllerState.ENGAGED:
            return None
        # Tracking a moving target, the trajectory can overshoot a limit by a hair. (np.clip's
        # dispatch costs more than the two ufuncs it amounts to, at 240 Hz.)
        lim = self._limits
        return ArmCommand(
            q_rad=np.minimum(np.maximum(self.trajectory.step(), lim.lower), lim.upper)
        )

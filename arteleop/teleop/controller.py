"""The robot side of the loop: from received wearable samples to arm and gripper commands.

States: CALIBRATING (collect the operator's initial posture hold), WAITING (calibrated; the arm
holds still until the operator's hand maps onto the gripper's current position, so engaging never
makes the arm jump) and ENGAGED (mapping -> IK -> trajectory -> position control at every tick).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from enum import Enum

import numpy as np
from numpy.typing import NDArray

from arteleop.operator import (
    ArmModel,
    CalibrationPosture,
    HandSample,
    SampleStatus,
    StreamingReconstructor,
)
from arteleop.operator.calibration import calibrate_from_hold
from arteleop.robot import GRIPPER_FRAME, RIGHT_ARM_JOINTS, WORK_POSTURE
from arteleop.robot.grip_control import GripCommand, GripHysteresis
from arteleop.robot.ik import ArmIK, IKConfig, IKResult
from arteleop.robot.mapping import HandToGripper, MappingConfig
from arteleop.robot.trajectory import JointTrajectory, TrajectoryLimits
from arteleop.scene import RemoteSite
from arteleop.teleop.hand_speed import HandSpeed
from arteleop.teleop.timing import StageTimer


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
    """

    mapping: MappingConfig = field(default_factory=MappingConfig)
    ik: IKConfig = field(default_factory=IKConfig)
    grip: GripHysteresis = field(default_factory=GripHysteresis)
    engage_distance_m: float = 0.05
    engage_speed_m_s: float = 0.05
    speed_window_s: float = 0.3
    max_gap_s: float = 0.1


class TeleopController:
    """Turns wearable samples into robot commands for one trial."""

    def __init__(
        self,
        site: RemoteSite,
        arm: ArmModel,
        posture: CalibrationPosture,
        control_dt_s: float,
        config: ControllerConfig | None = None,
        timer: StageTimer | None = None,
    ) -> None:
        self.config = c = config or ControllerConfig()
        self.timer = timer or StageTimer()
        """Times the ``mapping`` and ``ik`` stages of each control tick."""
        self.site = site
        self.arm = arm
        self.posture = posture
        self.dt = control_dt_s
        ws = site.config.workspace
        self._limits = limits = site.kinematics.limits(RIGHT_ARM_JOINTS)
        center = (*ws.table_center_xy_m, ws.table_top_z_m - ws.table_thickness_m / 2)
        half = (ws.table_size_m[0] / 2, ws.table_size_m[1] / 2, ws.table_thickness_m / 2)
        q0 = site.robot.arm_positions()
        self.ik = ArmIK(site.description.urdf_path, limits, WORK_POSTURE, center, half, c.ik)
        self.trajectory = JointTrajectory(
            TrajectoryLimits.from_joint_limits(limits), 1.0 / site.config.physics_rate_hz, q0
        )
        self.mapping = HandToGripper(c.mapping)
        self.grip = GripCommand(c.grip)
        self.state = ControllerState.CALIBRATING
        self._hold: list[NDArray[np.float64]] = []
        self._t0: float | None = None
        self.reconstructor: StreamingReconstructor | None = None
        self.last_hand: HandSample | None = None
        self._speed = HandSpeed(c.speed_window_s)
        self.last_ik: IKResult | None = None
        self._q_ik_prev = q0
        self.applied_sample_time_s = -np.inf  # newest operator sample acting on the arm
        self.unreachable_ticks = 0

    def receive(
        self, sample_time_s: float, sensor_quat_wxyz: NDArray[np.float64] | None, grip: float
    ) -> None:
        """A wearable sample arrived (``None`` quaternions: the sample was lost or invalid)."""
        if self.state is ControllerState.CALIBRATING:
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
        assert self.reconstructor is not None
        hand = self.reconstructor.update(sample_time_s, sensor_quat_wxyz, grip)
        if hand is None or hand.status is SampleStatus.LOST:
            return
        if self.last_hand is None or hand.time_s > self.last_hand.time_s:
            self._speed.update(hand.time_s, hand.hand_m)
        self.last_hand = hand

    @property
    def hand_speed_m_s(self) -> float:
        """The operator's hand speed (m/s) over the last ``speed_window_s``."""
        return self._speed.speed_m_s

    def control_tick(self) -> None:
        """Mapping, IK and a new trajectory target, from the newest hand sample."""
        hand = self.last_hand
        if hand is None or self.state is ControllerState.CALIBRATING:
            return
        w0 = time.perf_counter()
        target = self.mapping.gripper_target(hand.hand_m, hand.hand_quat_wxyz)
        self.timer.record("mapping", w0)
        if self.state is ControllerState.WAITING:
            gripper = self.site.robot.link_transform(GRIPPER_FRAME)[:3, 3]
            aligned = np.linalg.norm(target[:3, 3] - gripper) < self.config.engage_distance_m
            if not (aligned and self.hand_speed_m_s < self.config.engage_speed_m_s):
                return
            q = self.site.robot.arm_positions()
            self.ik.reset(q)
            self.trajectory.reset(q)
            self._q_ik_prev = q
            self.state = ControllerState.ENGAGED
        w0 = time.perf_counter()
        self.ik.set_target(target)
        result = self.ik.step(self.dt)
        self.timer.record("ik", w0)
        self.last_ik = result
        self.unreachable_ticks += not result.reachable
        self.trajectory.set_target(result.q_rad)
        self._q_ik_prev = result.q_rad
        self.site.robot.gripper.command(self.grip.update(hand.grip))
        self.applied_sample_time_s = hand.time_s

    def physics_tick(self) -> None:
        """One trajectory step, sent to the arm's position control."""
        if self.state is ControllerState.ENGAGED:
            # Tracking a moving target, the trajectory can overshoot a limit by a hair.
            lim = self._limits
            self.site.robot.command_arm(np.clip(self.trajectory.step(), lim.lower, lim.upper))

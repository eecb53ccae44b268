"""Jerk-limited joint trajectories with ruckig, from the current state to the IK's target.

Every control tick sets a new target (position and, so that a moving target is tracked without
stopping at each tick, a velocity); every physics step advances the trajectory by one step and
yields the position command for PyBullet's position control.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray
from ruckig import InputParameter, OutputParameter, Result, Ruckig

from arteleop.errors import ConfigurationError, TrajectoryError
from arteleop.robot.joints import JointLimits


@dataclass(frozen=True)
class TrajectoryLimits:
    """Kinematic limits for the trajectory, per joint in ``RIGHT_ARM_JOINTS`` order.

    Velocity limits come from the URDF. Acceleration and jerk are ours, chosen for a smooth,
    Baxter-like arm (its series-elastic actuators are slow): shoulder and elbow 4 rad/s^2 and
    40 rad/s^3; wrist 8 rad/s^2 and 80 rad/s^3.
    """

    velocity_rad_s: tuple[float, ...]
    acceleration_rad_s2: tuple[float, ...] = (4.0, 4.0, 4.0, 4.0, 8.0, 8.0, 8.0)
    jerk_rad_s3: tuple[float, ...] = (40.0, 40.0, 40.0, 40.0, 80.0, 80.0, 80.0)

    def __post_init__(self) -> None:
        for name in ("velocity_rad_s", "acceleration_rad_s2", "jerk_rad_s3"):
            values = np.asarray(getattr(self, name))
            if values.shape != (7,) or np.any(values <= 0):
                raise ConfigurationError(
                    f"TrajectoryLimits.{name} needs 7 positive values, got {values}"
                )

    @classmethod
    def from_joint_limits(cls, limits: JointLimits) -> TrajectoryLimits:
        return cls(velocity_rad_s=tuple(float(v) for v in limits.velocity))


class JointTrajectory:
    """Online jerk-limited trajectory generator for the arm's 7 joints."""

    def __init__(self, limits: TrajectoryLimits, dt_s: float, q0_rad: ArrayLike) -> None:
        self.limits = limits
        self.dt_s = dt_s
        self._otg = Ruckig(7, dt_s)
        self._inp = InputParameter(7)
        self._out = OutputParameter(7)
        self._inp.max_velocity = list(limits.velocity_rad_s)
        self._inp.max_acceleration = list(limits.acceleration_rad_s2)
        self._inp.max_jerk = list(limits.jerk_rad_s3)
        self.reset(q0_rad)

    def reset(self, q_rad: ArrayLike) -> None:
        """Rest at ``q_rad`` with zero velocity and acceleration."""
        q = np.asarray(q_rad, dtype=np.float64).tolist()
        self._inp.current_position = q
        self._inp.current_velocity = [0.0] * 7
        self._inp.current_acceleration = [0.0] * 7
        self._inp.target_position = q
        self._inp.target_velocity = [0.0] * 7
        self._inp.target_acceleration = [0.0] * 7

    def set_target(self, q_rad: ArrayLike, velocity_rad_s: ArrayLike | None = None) -> None:
        """New target position and (clipped to 90 % of the limits) target velocity."""
        self._inp.target_position = np.asarray(q_rad, dtype=np.float64).tolist()
        v = np.zeros(7) if velocity_rad_s is None else np.asarray(velocity_rad_s, dtype=np.float64)
        vmax = 0.9 * np.asarray(self.limits.velocity_rad_s)
        self._inp.target_velocity = np.clip(v, -vmax, vmax).tolist()

    def step(self) -> NDArray[np.float64]:
        """Advance by ``dt_s``; return the new position command (rad)."""
        result = self._otg.update(self._inp, self._out)
        if result not in (Result.Working, Result.Finished):
            raise TrajectoryError(
                f"ruckig could not plan a trajectory to the IK's target ({result}); the target "
                "or the current state is outside the limits of TrajectoryLimits."
            )
        self._out.pass_to_input(self._inp)
        return np.array(self._out.new_position)

    @property
    def position(self) -> NDArray[np.float64]:
        return np.array(self._inp.current_position)

    @property
    def velocity(self) -> NDArray[np.float64]:
        return np.array(self._inp.current_velocity)

    @property
    def acceleration(self) -> NDArray[np.float64]:
        return np.array(self._inp.current_acceleration)

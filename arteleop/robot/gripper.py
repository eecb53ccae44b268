"""Baxter's electric parallel gripper: one closure command drives both prismatic fingers."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pybullet as p
from pybullet_utils.bullet_client import BulletClient

from arteleop.errors import ArmCommandError, ArteleopError, ConfigurationError
from arteleop.robot.joints import JointLimits


@dataclass(frozen=True)
class GripperConfig:
    """Electric gripper settings.

    Attributes:
        max_force_n: Force limit of each finger motor (N). Holding a 0.1 kg bowl with friction
            coefficient 1 needs 2 * mu * F >= m * g, i.e. F >= 0.5 N; 15 N leaves a wide margin
            yet is below the URDF's 20 N effort, so fingers stop on the wall instead of pushing
            through it.
        max_speed_m_s: Finger speed limit (m/s); the real gripper closes in about half a second.
        pad_friction: Lateral friction coefficient of the finger pads.
    """

    max_force_n: float = 15.0
    max_speed_m_s: float = 0.05
    pad_friction: float = 1.5

    def __post_init__(self) -> None:
        for name in ("max_force_n", "max_speed_m_s", "pad_friction"):
            if getattr(self, name) <= 0:
                raise ConfigurationError(
                    f"GripperConfig.{name} must be > 0, got {getattr(self, name)}"
                )


class ElectricGripper:
    """Closure 0 (open) .. 1 (closed) mapped linearly onto both finger joints.

    The left finger joint opens towards +q, the right one towards -q (the URDF's mimic pair).
    """

    def __init__(
        self,
        client: BulletClient,
        body_id: int,
        finger_joints: tuple[int, int],
        finger_links: tuple[int, int],
        finger_limits: JointLimits,
        config: GripperConfig | None = None,
    ) -> None:
        self._client = client
        self._body = body_id
        self._joints = finger_joints
        self._fingers = finger_links
        self.config = config or GripperConfig()
        self.stroke_m = float(finger_limits.upper[0])  # travel of each finger, open minus closed
        self._closure_command = 0.0
        for link in finger_links:
            client.changeDynamics(body_id, link, lateralFriction=self.config.pad_friction)

    def _finger_targets(self, closure: float) -> tuple[float, float]:
        q = self.stroke_m * (1.0 - closure)
        return q, -q

    def reset(self, closure: float) -> None:
        """Teleport the fingers to ``closure`` and hold them there."""
        for j, q in zip(
            self._joints, self._finger_targets(_check(closure, ConfigurationError)), strict=True
        ):
            self._client.resetJointState(self._body, j, q)
        self.command(closure)

    def command(self, closure: float) -> None:
        """Drive the fingers towards ``closure`` (0 open, 1 closed) with limited force and speed."""
        self._closure_command = _check(closure, ArmCommandError)
        for j, q in zip(self._joints, self._finger_targets(self._closure_command), strict=True):
            self._client.setJointMotorControl2(
                self._body,
                j,
                p.POSITION_CONTROL,
                targetPosition=q,
                force=self.config.max_force_n,
                maxVelocity=self.config.max_speed_m_s,
            )

    @property
    def commanded_closure(self) -> float:
        return self._closure_command

    def closure(self) -> float:
        """Measured closure, 0..1, from the mean finger displacement."""
        (ql, *_), (qr, *_) = self._client.getJointStates(self._body, self._joints)
        return min(1.0, max(0.0, 1.0 - 0.5 * (ql - qr) / self.stroke_m))

    def pad_gap_m(self) -> float:
        """Current distance (m) between the two finger pads' collision surfaces."""
        pts = self._client.getClosestPoints(
            self._body, self._body, 1.0, linkIndexA=self._fingers[0], linkIndexB=self._fingers[1]
        )
        return float(min(pt[8] for pt in pts)) if pts else float("inf")

    def touching(self, body_id: int) -> tuple[bool, bool]:
        """Whether the (left, right) finger is in contact with ``body_id``."""
        return tuple(
            bool(self._client.getContactPoints(self._body, body_id, linkIndexA=link))
            for link in self._fingers
        )  # type: ignore[return-value]


def _check(closure: float, error: type[ArteleopError]) -> float:
    if not np.isfinite(closure) or not 0.0 <= closure <= 1.0:
        raise error(f"gripper closure must be in [0, 1] (0 open, 1 closed), got {closure}")
    return float(closure)

"""Forward kinematics of Baxter with pinocchio, on the same URDF that PyBullet loads."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np
import pinocchio as pin
from numpy.typing import NDArray

from arteleop.errors import ConfigurationError
from arteleop.robot.joints import JointLimits


class BaxterKinematics:
    """Pinocchio model of Baxter with a fixed base; the world frame is Baxter's ``base`` link.

    Configurations are given by joint name (:meth:`configuration`); joints not named stay at 0.
    """

    def __init__(self, urdf_path: Path) -> None:
        self.model = pin.buildModelFromUrdf(str(urdf_path))
        self.data = self.model.createData()
        # Every movable joint in Baxter has one coordinate (revolute or prismatic).
        self.joint_names: tuple[str, ...] = tuple(self.model.names[1:])
        self._q_index = {
            name: self.model.joints[self.model.getJointId(name)].idx_q for name in self.joint_names
        }

    def configuration(self, positions: Mapping[str, float]) -> NDArray[np.float64]:
        """Pinocchio configuration vector from joint name -> position (rad or m)."""
        q = pin.neutral(self.model)
        for name, value in positions.items():
            if name not in self._q_index:
                raise ConfigurationError(
                    f"Unknown joint '{name}'. Baxter's movable joints: {list(self.joint_names)}"
                )
            q[self._q_index[name]] = value
        return q

    def frame_transform(self, positions: Mapping[str, float], frame: str) -> NDArray[np.float64]:
        """``T_base_frame`` (4x4) for the named link or joint frame at the given positions."""
        return self.frame_transforms(positions, (frame,))[0]

    def frame_transforms(
        self, positions: Mapping[str, float], frames: Sequence[str]
    ) -> list[NDArray[np.float64]]:
        """``T_base_frame`` for several frames, with one forward-kinematics pass."""
        ids = [self._frame_id(f) for f in frames]
        pin.framesForwardKinematics(self.model, self.data, self.configuration(positions))
        return [self.data.oMf[i].homogeneous.copy() for i in ids]

    def limits(self, names: Sequence[str]) -> JointLimits:
        """URDF limits of the named joints, in the given order."""
        idx = [self._q_index[n] if n in self._q_index else self._unknown(n) for n in names]
        return JointLimits(
            names=tuple(names),
            lower=self.model.lowerPositionLimit[idx],
            upper=self.model.upperPositionLimit[idx],
            velocity=self.model.velocityLimit[idx],
            effort=self.model.effortLimit[idx],
        )

    def _frame_id(self, frame: str) -> int:
        if not self.model.existFrame(frame):
            names = sorted({f.name for f in self.model.frames})
            raise ConfigurationError(f"Unknown frame '{frame}'. Baxter's frames: {names}")
        return self.model.getFrameId(frame)

    def _unknown(self, name: str) -> int:
        raise ConfigurationError(
            f"Unknown joint '{name}'. Baxter's movable joints: {list(self.joint_names)}"
        )

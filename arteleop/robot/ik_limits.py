"""mink's joint limits with the rows that do not change between IK steps kept.

mink builds every inequality row of its QP again at every step. For a chain of hinge joints,
the velocity limit's rows depend only on the step's duration and the position limit's matrix
not at all on the configuration; rebuilding them cost as much as daqp's solve. These
subclasses keep what is fixed and compute the rest with the same operations, so the rows, and
the IK's joints, are the same to the bit (tests compare them with mink's own).
"""

from __future__ import annotations

import mink
import mujoco
import numpy as np
from mink.limits import Constraint

from arteleop.errors import ConfigurationError


class KeptVelocityLimit(mink.VelocityLimit):
    """:class:`mink.VelocityLimit` whose rows are built once per step duration."""

    def __init__(self, model: mujoco.MjModel, velocities: dict[str, float]) -> None:
        super().__init__(model, velocities)
        self._kept: tuple[float, Constraint] | None = None

    def compute_qp_inequalities(self, configuration: mink.Configuration, dt: float) -> Constraint:
        if self._kept is None or self._kept[0] != dt:
            self._kept = (dt, super().compute_qp_inequalities(configuration, dt))
        return self._kept[1]


class HingeConfigurationLimit(mink.ConfigurationLimit):
    """:class:`mink.ConfigurationLimit` of a model with hinge and slide joints only: the rows'
    matrix is built once; the bounds ``gain * (upper - q)`` and ``gain * (q - lower)`` are what
    ``mj_differentiatePos`` gives for such joints."""

    def __init__(self, model: mujoco.MjModel) -> None:
        super().__init__(model)
        scalar = {int(mujoco.mjtJoint.mjJNT_HINGE), int(mujoco.mjtJoint.mjJNT_SLIDE)}
        if not set(model.jnt_type.tolist()) <= scalar:
            raise ConfigurationError(
                "HingeConfigurationLimit needs hinge or slide joints only; use "
                "mink.ConfigurationLimit for a model with ball or free joints."
            )
        self._G = np.vstack([self.projection_matrix, -self.projection_matrix])

    def compute_qp_inequalities(self, configuration: mink.Configuration, dt: float) -> Constraint:
        del dt  # unused, as in mink
        q = configuration.q
        # Scalar joints: qpos and qvel share their addresses, and mj_differentiatePos's
        # difference over dt = 1 is the plain one.
        p_max = self.gain * (self.upper - q)[self.indices]
        p_min = self.gain * (q - self.lower)[self.indices]
        return Constraint(G=self._G, h=np.hstack([p_max, p_min]))

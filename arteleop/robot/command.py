"""What the robot side sends the arm: plain data, checked when it is made."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from arteleop.arrays import frozen_array
from arteleop.errors import ArmCommandError
from arteleop.robot.joints import RIGHT_ARM_JOINTS


@dataclass(frozen=True)
class ArmCommand:
    """One command to the right arm and its gripper; a part left ``None`` stays as it was.

    Attributes:
        q_rad: (7,) joint position targets in ``RIGHT_ARM_JOINTS`` order (rad). The site checks
            them against the joint limits when it applies them.
        gripper_closure: Gripper closure target, 0 (open) .. 1 (closed).
    """

    q_rad: NDArray[np.float64] | None = None
    gripper_closure: float | None = None

    def __post_init__(self) -> None:
        if self.q_rad is not None:
            q = frozen_array(self.q_rad)
            # The sum is finite only if every entry is: one check instead of seven.
            if q.shape != (len(RIGHT_ARM_JOINTS),) or not np.isfinite(q.sum()):
                raise ArmCommandError(
                    f"ArmCommand.q_rad must be {len(RIGHT_ARM_JOINTS)} finite joint positions "
                    f"(rad) in the order {RIGHT_ARM_JOINTS}; got {np.asarray(self.q_rad)!r}"
                )
            object.__setattr__(self, "q_rad", q)
        c = self.gripper_closure
        if c is not None and not (np.isfinite(c) and 0.0 <= c <= 1.0):
            raise ArmCommandError(
                f"ArmCommand.gripper_closure must be in [0, 1] (0 open, 1 closed); got {c}"
            )

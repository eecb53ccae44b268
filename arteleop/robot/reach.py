"""Can the right gripper reach a point from above? A geometric check on the kinematic model.

With the gripper pointing straight down, the wrist centre (joint ``right_w1``) sits a fixed
distance above the tool frame, because ``w1 -> w2 -> hand -> gripper`` are collinear along the
tool axis. The point is then reachable only if the wrist centre lies within the shell that the
shoulder (``right_s1``) can reach with the elbow between its limits. This is a necessary
condition; the inverse kinematics checks the rest when the arm moves.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from arteleop.robot.joints import GRIPPER_FRAME
from arteleop.robot.kinematics import BaxterKinematics


@dataclass(frozen=True)
class TopDownReach:
    """Reach of Baxter's right arm for a gripper pointing down, in the base frame (m)."""

    shoulder_m: NDArray[np.float64]
    wrist_to_tool_m: float
    max_reach_m: float
    min_reach_m: float

    @classmethod
    def from_kinematics(cls, kinematics: BaxterKinematics) -> TopDownReach:
        names = ("right_s1", "right_e1", "right_w1", GRIPPER_FRAME)
        s1, e1, w1, tool = (T[:3, 3] for T in kinematics.frame_transforms({}, names))
        upper, fore = np.linalg.norm(e1 - s1), np.linalg.norm(w1 - e1)
        e1_max = float(kinematics.limits(("right_e1",)).upper[0])
        # Law of cosines at the most-folded elbow gives the nearest reachable wrist distance.
        min_reach = np.sqrt(upper**2 + fore**2 - 2 * upper * fore * np.cos(np.pi - e1_max))
        return cls(
            shoulder_m=s1,
            wrist_to_tool_m=float(np.linalg.norm(tool - w1)),
            max_reach_m=float(upper + fore),
            min_reach_m=float(min_reach),
        )

    def reach_fraction(self, tool_position_m: NDArray[np.float64]) -> float:
        """Distance shoulder -> wrist centre as a fraction of the arm's maximum reach."""
        wrist = np.asarray(tool_position_m, dtype=np.float64) + np.array(
            [0.0, 0.0, self.wrist_to_tool_m]
        )
        return float(np.linalg.norm(wrist - self.shoulder_m) / self.max_reach_m)

    def is_reachable(self, tool_position_m: NDArray[np.float64], margin: float = 0.05) -> bool:
        """True if the wrist centre is between the minimum and (1 - margin) of the maximum reach."""
        f = self.reach_fraction(tool_position_m)
        return self.min_reach_m / self.max_reach_m <= f <= 1.0 - margin

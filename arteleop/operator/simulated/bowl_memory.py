"""Where the operator believes the bowl is while the display does not show it: where it was last
seen, or, held, where it sits in the hand."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

if TYPE_CHECKING:
    from arteleop.operator.simulated.perception import Perceived


class BowlMemory:
    """Where the operator believes the bowl is: where a look last showed it, and while it is
    held, where it sits relative to the gripper (it moves with the hand), with the covariance
    (m^2) of that judgement from the grasp."""

    def __init__(self) -> None:
        self._last_seen_m: NDArray[np.float64] | None = None
        self._in_hand_m: NDArray[np.float64] | None = None
        self.in_hand_cov = np.zeros((3, 3))

    def bowl_m(self, seen: Perceived) -> NDArray[np.float64] | None:
        """The bowl after a look: as seen when shown, else as remembered; None before it was
        ever seen."""
        if seen.bowl_m is not None:
            # Held, it is where the judged gripper carries it, ahead of the frame by the lead.
            present = seen.bowl_m + seen.lead_m if self._in_hand_m is not None else seen.bowl_m
            self._last_seen_m = present
            return present
        if self._in_hand_m is not None:
            return seen.gripper_m + self._in_hand_m
        return self._last_seen_m

    @property
    def holding(self) -> bool:
        return self._in_hand_m is not None

    def grasp(self, seen: Perceived, bowl_m: NDArray[np.float64] | None) -> None:
        """The operator has closed the gripper on the bowl believed at ``bowl_m``; the bowl's
        place in the hand is as uncertain as the grasp's judgement was."""
        self._in_hand_m = None if bowl_m is None else bowl_m - seen.gripper_m
        self.in_hand_cov = seen.gripper_cov.copy()

    def release(self) -> None:
        self._in_hand_m = None
        self.in_hand_cov = np.zeros((3, 3))

    def left_behind(self, seen: Perceived, drop_m: float = 0.07) -> bool:
        """A look shows the bowl held a moment ago away from where the hand holds it: more than
        ``drop_m`` below where the hand should carry it, or farther than ``drop_m`` beyond the
        reach of the hold from the gripper (the bowl's frame is where the grasp found it from
        the grasp point, however the bowl swings about it). The grasp missed and the bowl
        stayed on the table. (A held bowl hangs from its rim and the estimates err by
        centimetres, but a lift is 15 cm; and lowering, a bowl left on the table is no longer
        far below the hand, but as far from it as it was from the target.)"""
        if seen.bowl_m is None or self._in_hand_m is None:
            return False
        # Compared within the frame the bowl is seen in: its own gripper, not the lead's.
        gripper = seen.gripper_m - seen.lead_m
        below = (gripper + self._in_hand_m)[2] - seen.bowl_m[2]
        beyond = np.linalg.norm(seen.bowl_m - gripper) - np.linalg.norm(self._in_hand_m)
        return bool(below > drop_m or beyond > drop_m)

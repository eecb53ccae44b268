"""What an operator, synthetic or a person live, gives the loop at each sample (its hand, its
grip, its phase), and the operator's own phases around the task's."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

CALIBRATE = "calibrate"
"""The operator's phase while it holds the calibration posture."""
ALIGN = "align"
"""...while it brings the hand to where it commands the resting gripper."""
ENGAGE = "engage"
"""...while it waits for the display to show the robot engaged."""
DONE = "done"
"""...once the task's last phase is over."""


@dataclass(frozen=True)
class OperatorOutput:
    """The operator's hand at one sample: torso frame. ``phase`` is the name of the operator's
    phase (:data:`CALIBRATE`, :data:`ALIGN`, :data:`ENGAGE`, one of the task's, :data:`DONE`)."""

    time_s: float
    hand_m: NDArray[np.float64]
    R_torso_hand: NDArray[np.float64]
    grip: float
    phase: str

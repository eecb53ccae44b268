"""What a trial records at every control tick (100 Hz): the study's trajectory files.

One row per control tick: the operator's reconstructed hand (torso frame, the operator's frame),
its grip, the three IMU quaternions as received, the gripper's target from the mapping and the
gripper's actual position (Baxter's base frame) and closure, the right arm's joint positions and
the bowl's true position. A value the robot side did not have yet (before calibration, a lost
sample) is NaN.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from arteleop.operator import SEGMENTS
from arteleop.robot import RIGHT_ARM_JOINTS

TRACE_COLUMNS: tuple[str, ...] = (
    "time_s",
    "hand_x_m", "hand_y_m", "hand_z_m",
    "grip",
    *(f"{s}_q{c}" for s in SEGMENTS for c in "wxyz"),
    "gripper_target_x_m", "gripper_target_y_m", "gripper_target_z_m",
    "gripper_x_m", "gripper_y_m", "gripper_z_m", "gripper_closure",
    *(f"{j}_rad" for j in RIGHT_ARM_JOINTS),
    "bowl_x_m", "bowl_y_m", "bowl_z_m",
)  # fmt: skip
"""The trace's columns, in order: a public format (docs/reference/data-format.md, trajectory
files)."""

_NAN3 = np.full(3, np.nan)
_NAN_QUATS = np.full(4 * len(SEGMENTS), np.nan)


class TrialTrace:
    """Collects one row of :data:`TRACE_COLUMNS` per control tick."""

    def __init__(self) -> None:
        self._rows: list[NDArray[np.float64]] = []

    def add(
        self,
        time_s: float,
        hand_m: NDArray[np.float64] | None,
        grip: float,
        sensor_quat_wxyz: NDArray[np.float64] | None,
        gripper_target_m: NDArray[np.float64] | None,
        gripper_m: NDArray[np.float64],
        gripper_closure: float,
        arm_q_rad: NDArray[np.float64],
        bowl_m: NDArray[np.float64],
    ) -> None:
        """One tick; ``None`` for what the robot side does not know yet (written as NaN)."""
        quats = _NAN_QUATS if sensor_quat_wxyz is None else np.ravel(sensor_quat_wxyz)
        hand = _NAN3 if hand_m is None else hand_m
        target = _NAN3 if gripper_target_m is None else gripper_target_m
        parts = ((time_s,), hand, (grip,), quats, target, gripper_m, (gripper_closure,),
                 arm_q_rad, bowl_m)  # fmt: skip
        self._rows.append(np.concatenate(parts))

    def columns(self) -> dict[str, NDArray[np.float64]]:
        """The trace as named columns, each (ticks,)."""
        table = np.array(self._rows).reshape(-1, len(TRACE_COLUMNS))
        return {name: table[:, k].copy() for k, name in enumerate(TRACE_COLUMNS)}

"""Display frames for tests, built by hand: the view and the operator take plain data."""

from __future__ import annotations

from typing import Any

import numpy as np

from arteleop.ar_features import ArCues, DisplayFrame
from arteleop.transforms import make_transform

# A head camera above and behind the table looking down at it, and a gripper over the start.
CAMERA_M = (0.22, 0.0, 0.89)
GRIPPER_M = (0.68, -0.37, -0.05)


def display_frame(**overrides: Any) -> DisplayFrame:
    """A frame of the task's geometry: gripper over the bowl at the start, target beside it."""
    fields: dict[str, Any] = {
        "time_s": 0.0,
        "T_base_camera": make_transform(np.eye(3), CAMERA_M),
        "arm_q_rad": np.zeros(7),
        "T_base_gripper": make_transform(np.diag([1.0, -1.0, -1.0]), GRIPPER_M),
        "gripper_closure": 0.0,
        "gripper_in_camera": True,
        "bowl_m": np.array([0.68, -0.45, -0.2]),
        "grasp_radius_m": 0.078,
        "grasp_height_m": 0.055,
        "target_m": np.array([0.68, -0.10, -0.2]),
        "cues": ArCues(),
        "engaged": True,
    }
    fields.update(overrides)
    return DisplayFrame(**fields)

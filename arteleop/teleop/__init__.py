"""The teleoperation loop: clock, network link, the robot side (the wearable's calibration, the
hand's reconstruction and filter, the controller), task monitor, display feed, timing and
trials; the live application.

The live application, which pulls in viser's server, is imported on first use.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from arteleop.teleop.clock import LoopClock, LoopRates, Tick
from arteleop.teleop.controller import (
    ControllerConfig,
    ControllerState,
    OperatorBody,
    TeleopController,
)
from arteleop.teleop.display_feed import DisplayFeed, display_frame, site_frame, view_assets
from arteleop.teleop.hand_filter import HandFilter, HandFilterConfig, filter_hand_path
from arteleop.teleop.hand_speed import HandSpeed
from arteleop.teleop.latency import LatencyAccount
from arteleop.teleop.loop import display_frame_at, display_frames_at, run_trial, trial_operator
from arteleop.teleop.network import NetworkConfig, NetworkLink
from arteleop.teleop.reconstruction import (
    HandSample,
    HandTrajectory,
    SampleStatus,
    StreamingReconstructor,
    reconstruct,
)
from arteleop.teleop.sensor_calibration import SensorMounting, calibrate, calibrate_from_hold
from arteleop.teleop.task_monitor import PointingMonitor, SelectionMonitor, TaskMonitor
from arteleop.teleop.timing import StageStats, StageTimer
from arteleop.teleop.trace import TRACE_COLUMNS, TrialTrace
from arteleop.teleop.trial import Outcome, TrialConfig, TrialProgress, TrialResult
from arteleop.teleop.trial_task import (
    PERSON_POINTING,
    PICK_AND_PLACE,
    POINTING,
    TASKS,
    TaskSite,
    TrialTask,
    trial_task,
)

if TYPE_CHECKING:
    from arteleop.teleop.live_app import TeleopApp, TeleopAppConfig, TrialInterrupted

_LAZY = {
    "TeleopApp": "arteleop.teleop.live_app",
    "TeleopAppConfig": "arteleop.teleop.live_app",
    "TrialInterrupted": "arteleop.teleop.live_app",
}

__all__ = [
    "PERSON_POINTING",
    "PICK_AND_PLACE",
    "POINTING",
    "TASKS",
    "TRACE_COLUMNS",
    "ControllerConfig",
    "ControllerState",
    "DisplayFeed",
    "HandFilter",
    "HandFilterConfig",
    "HandSample",
    "HandSpeed",
    "HandTrajectory",
    "LatencyAccount",
    "LoopClock",
    "LoopRates",
    "NetworkConfig",
    "NetworkLink",
    "OperatorBody",
    "Outcome",
    "PointingMonitor",
    "SampleStatus",
    "SelectionMonitor",
    "SensorMounting",
    "StageStats",
    "StageTimer",
    "StreamingReconstructor",
    "TaskMonitor",
    "TaskSite",
    "TeleopApp",
    "TeleopAppConfig",
    "TeleopController",
    "Tick",
    "TrialConfig",
    "TrialInterrupted",
    "TrialProgress",
    "TrialResult",
    "TrialTask",
    "TrialTrace",
    "calibrate",
    "calibrate_from_hold",
    "display_frame",
    "display_frame_at",
    "display_frames_at",
    "filter_hand_path",
    "reconstruct",
    "run_trial",
    "site_frame",
    "trial_operator",
    "trial_task",
    "view_assets",
]


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        return getattr(importlib.import_module(_LAZY[name]), name)
    raise AttributeError(f"module 'arteleop.teleop' has no attribute '{name}'")

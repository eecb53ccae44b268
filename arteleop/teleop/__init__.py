"""The teleoperation loop: clock, network link, robot-side controller, task monitor, display
feed, timing and trials."""

from arteleop.teleop.clock import LoopClock, LoopRates, Tick
from arteleop.teleop.controller import (
    ControllerConfig,
    ControllerState,
    OperatorBody,
    TeleopController,
)
from arteleop.teleop.display_feed import DisplayFeed, display_frame, view_assets
from arteleop.teleop.hand_speed import HandSpeed
from arteleop.teleop.latency import LatencyAccount
from arteleop.teleop.loop import display_frame_at, run_trial
from arteleop.teleop.network import NetworkConfig, NetworkLink
from arteleop.teleop.task_monitor import TaskMonitor
from arteleop.teleop.timing import StageStats, StageTimer
from arteleop.teleop.trial import Outcome, TrialConfig, TrialResult

__all__ = [
    "ControllerConfig",
    "ControllerState",
    "DisplayFeed",
    "HandSpeed",
    "LatencyAccount",
    "LoopClock",
    "LoopRates",
    "NetworkConfig",
    "NetworkLink",
    "OperatorBody",
    "Outcome",
    "StageStats",
    "StageTimer",
    "TaskMonitor",
    "TeleopController",
    "Tick",
    "TrialConfig",
    "TrialResult",
    "display_frame",
    "display_frame_at",
    "run_trial",
    "view_assets",
]

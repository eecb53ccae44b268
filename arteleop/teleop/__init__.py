"""The teleoperation loop: clock, network link, robot-side controller, timing and trials."""

from arteleop.teleop.clock import LoopClock, LoopRates, Tick
from arteleop.teleop.controller import ControllerConfig, ControllerState, TeleopController
from arteleop.teleop.hand_speed import HandSpeed
from arteleop.teleop.network import NetworkConfig, NetworkLink
from arteleop.teleop.setup import synthetic_source
from arteleop.teleop.sources import OperatorSource, RecordingSource, SyntheticSource, WearableSample
from arteleop.teleop.timing import StageStats, StageTimer
from arteleop.teleop.trial import CloudDisplay, TrialConfig, TrialResult, run_trial

__all__ = [
    "CloudDisplay",
    "ControllerConfig",
    "ControllerState",
    "HandSpeed",
    "LoopClock",
    "LoopRates",
    "NetworkConfig",
    "NetworkLink",
    "OperatorSource",
    "RecordingSource",
    "StageStats",
    "StageTimer",
    "SyntheticSource",
    "TeleopController",
    "Tick",
    "TrialConfig",
    "TrialResult",
    "WearableSample",
    "run_trial",
    "synthetic_source",
]

"""The `arteleop` command. Each subcommand's options map one-to-one onto a config dataclass.

One module per command group (``scene``, ``calibrate``, ``operator``, ``trial`` with ``teleop``,
``study``, ``analyze``); what they share is in ``options`` (the camera's size and registration,
the seed), ``progress``, ``interrupt`` (Ctrl-C) and ``main`` (the command table).
"""

from arteleop.cli.analyze import AnalyzeCommand
from arteleop.cli.calibrate import CalibrateCommand
from arteleop.cli.main import COMMANDS, GROUPS, OVERVIEW, main
from arteleop.cli.operator import OperatorCheckCommand, OperatorSynthCommand
from arteleop.cli.options import CameraSize, Modality
from arteleop.cli.scene import SceneCommand
from arteleop.cli.study import (
    StudyAnswerCommand,
    StudyInitCommand,
    StudyReplayCommand,
    StudyResumeCommand,
    StudyRunCommand,
)
from arteleop.cli.trial import TeleopCommand, TrialCommand

__all__ = [
    "COMMANDS",
    "GROUPS",
    "OVERVIEW",
    "AnalyzeCommand",
    "CalibrateCommand",
    "CameraSize",
    "Modality",
    "OperatorCheckCommand",
    "OperatorSynthCommand",
    "SceneCommand",
    "StudyAnswerCommand",
    "StudyInitCommand",
    "StudyReplayCommand",
    "StudyResumeCommand",
    "StudyRunCommand",
    "TeleopCommand",
    "TrialCommand",
    "main",
]

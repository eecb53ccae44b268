"""The command table and the entry point of the `arteleop` command."""

from __future__ import annotations

import os
import signal
import sys
import threading
from collections.abc import Callable
from typing import Any

import tyro

from arteleop.cli.analyze import AnalyzeCommand, analyze
from arteleop.cli.calibrate import CalibrateCommand, calibrate
from arteleop.cli.interrupt import CTRL_C, on_ctrl_c
from arteleop.cli.operator import (
    OperatorCheckCommand,
    OperatorSynthCommand,
    operator_check,
    operator_synth,
)
from arteleop.cli.power import StudyPowerCommand, study_power
from arteleop.cli.scene import SceneCommand, scene
from arteleop.cli.study import (
    StudyAnswerCommand,
    StudyInitCommand,
    StudyReplayCommand,
    StudyResumeCommand,
    StudyRunCommand,
    StudyServeCommand,
    study_answer,
    study_init,
    study_replay,
    study_resume,
    study_run,
    study_serve,
)
from arteleop.cli.trial import TeleopCommand, TrialCommand, teleop, trial
from arteleop.errors import ArteleopError

Command = tuple[type, Callable[[Any], int]]


COMMANDS: dict[str, Command] = {
    "trial": (TrialCommand, trial),
    "teleop": (TeleopCommand, teleop),
    "scene": (SceneCommand, scene),
    "calibrate": (CalibrateCommand, calibrate),
    "analyze": (AnalyzeCommand, analyze),
}


GROUPS: dict[str, dict[str, Command]] = {
    "operator": {
        "synth": (OperatorSynthCommand, operator_synth),
        "check": (OperatorCheckCommand, operator_check),
    },
    "study": {
        "init": (StudyInitCommand, study_init),
        "run": (StudyRunCommand, study_run),
        "resume": (StudyResumeCommand, study_resume),
        "serve": (StudyServeCommand, study_serve),
        "answer": (StudyAnswerCommand, study_answer),
        "replay": (StudyReplayCommand, study_replay),
        "power": (StudyPowerCommand, study_power),
    },
}


MOVED_OPTIONS = {
    ("analyze", "study power"): {
        "--trim": "--method thesis is the thesis's trimming (it rejects a true null about twice "
        "as often as p <= 0.05 says); the default, --method untrimmed, keeps everyone",
        "--no-trim": "the default, --method untrimmed, keeps everyone; --method yuen compares "
        "20 % trimmed means at their stated error rate",
    },
}
"""Options that are gone, per command: what to give instead (0.3 -> 0.4)."""


OVERVIEW = """\
arteleop: study Augmented Reality in robot teleoperation, in simulation (docs/explanation/study.md).

commands:
  trial            one pick-and-place trial, by a synthetic operator or a recording;
                   --view serves the operator's view with its AR layers in the browser
  teleop           teleoperate in real time in the browser, trial after trial: a synthetic
                   participant, a recording, or you (--operator live: gizmo and grip slider)
  scene            render one head-camera frame, write it, and track the bowl
  calibrate        register the head camera to the robot (ArUco on the table; hand-eye with
                   a board in the gripper), score it against the truth, write the graph file
  operator synth   one synthetic trial, written as the operator's wearable recording
  operator check   validate a wearable recording and summarise it
  study run        run a study (the default: 22 simulated participants, five modalities)
                   into a run folder, then its analysis and report
  study init       write the default study definition (TOML) to edit
  study resume     continue a run folder after a crash, Ctrl-C or kill
  study answer     merge real questionnaire answers into a run folder
  study replay     play a trial of a run folder back in the operator's view
  study power      how many participants a design needs: power by resampling a pilot
  analyze          the study's statistics, figures and report from its CSV files;
                   several run folders of one design: its answer pooled over them

'arteleop COMMAND --help' lists a command's options."""


def main(argv: list[str] | None = None) -> int:
    """Entry point of the `arteleop` command."""
    argv = sys.argv[1:] if argv is None else list(argv)
    if (
        threading.current_thread() is threading.main_thread()
        and signal.getsignal(signal.SIGINT) is signal.default_int_handler
    ):
        signal.signal(signal.SIGINT, on_ctrl_c)
    if not argv or argv[0] in ("-h", "--help"):
        print(OVERVIEW, file=sys.stdout if argv else sys.stderr)
        return 0 if argv else 2
    if argv[0] in GROUPS:
        commands, prog, args = GROUPS[argv[0]], f"arteleop {argv[0]}", argv[1:]
    else:
        commands, prog, args = COMMANDS, "arteleop", argv
    if moved := _moved_option(argv):
        print(f"arteleop: error: {moved}", file=sys.stderr)
        return 2
    try:
        cmd = tyro.extras.subcommand_cli_from_dict(
            {name: cfg for name, (cfg, _) in commands.items()},
            prog=prog,
            args=args,
            description=OVERVIEW,
        )
        run = next(fn for cfg, fn in commands.values() if isinstance(cmd, cfg))
        return run(cmd)
    except ArteleopError as err:
        print(f"arteleop: error: {err}", file=sys.stderr)
        return 2
    except KeyboardInterrupt as stop:
        print(f"arteleop: interrupted{'; ' + str(stop) if str(stop) else ''}", file=sys.stderr)
        return 130
    except ImportError as err:
        if CTRL_C.is_set():  # interrupted while importing: nothing of the user's is pending
            print("arteleop: interrupted", file=sys.stderr, flush=True)
            sys.stdout.flush()
            os._exit(130)  # a half-imported open3d's exit handlers print a leak report, exit 1
        if "libusb" not in str(err):
            raise
        print(
            "arteleop: error: open3d needs the system library libusb-1.0, which is missing. "
            "Install it: 'apt-get install libusb-1.0-0' on Debian or Ubuntu, 'dnf install "
            "libusbx' on Fedora, 'brew install libusb' on macOS.",
            file=sys.stderr,
        )
        return 2


def _moved_option(argv: list[str]) -> str:
    """What to give instead of an option that is gone, or ''."""
    for names, options in MOVED_OPTIONS.items():
        if any(argv[: len(name.split())] == name.split() for name in names):
            for option, instead in options.items():
                if option in argv:
                    return f"{option} is gone: {instead}."
    return ""

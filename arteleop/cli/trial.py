"""'arteleop trial' (one trial, optionally in the browser) and 'arteleop teleop' (trial after
trial, in real time)."""

from __future__ import annotations

import contextlib
import math
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from arteleop.cli.options import CameraSize, Modality, Renderer, check_seed
from arteleop.cli.progress import trial_progress
from arteleop.errors import ConfigurationError

if TYPE_CHECKING:
    from arteleop.operator import OperatorTraits
    from arteleop.teleop import HandFilterConfig, TrialResult


@dataclass(frozen=True)
class TrialCommand(CameraSize):
    """Run one pick-and-place trial and print its outcome; headless unless --view."""

    operator: str = "synthetic"
    """'synthetic' (a simulated participant), or the path of a wearable recording's CSV"""
    modality: Modality = "full"
    """AR modality shown to the operator (docs/explanation/study.md §3)"""
    seed: int = 0
    """seed of every random source of the trial (0 or more)"""
    delay_ms: float = 0.0
    """one-way network delay between operator and robot (ms)"""
    timeout_s: float = 120.0
    """simulated time after which the trial ends as a timeout (s)"""
    confidence: float = 0.95
    """synthetic operator: how sure it must be that the error is within its criterion to stop correcting (0.5-0.999; docs/explanation/operator-model.md)"""
    placement_criterion_m: float = 0.010
    """synthetic operator: how close to the target it holds good enough (0.001-0.1 m)"""
    filter_min_cutoff_hz: float = 1.0
    """the 1-euro filter on the operator's hand: cutoff at rest (0.01-100 Hz)"""
    filter_beta: float = 5.0
    """the 1-euro filter: how fast its cutoff rises with the hand's speed (0-1000 Hz per m/s)"""
    no_filter: bool = False
    """send the reconstructed hand to the robot unfiltered"""
    realtime: bool = False
    """pace the loop with the wall clock"""
    view: bool = False
    """serve the operator's view (point cloud and AR layers) in the browser, in real time"""
    depth_aids: bool = False
    """draw the depth aids in the view: the gripper's drop line to the table, a ring at its foot and its height (the simulated participant judges them too)"""
    task: str = "pick-and-place"
    """what the trial asks and how it is scored: pick-and-place, or a task of your own as package.module:NAME (docs/guides/extending.md)"""
    exit_when_done: bool = False
    """with --view: stop when the trial ends (else the view keeps its last frame until Ctrl-C)"""
    host: str = "127.0.0.1"
    """interface for --view; 0.0.0.0 lets other machines connect (and drive the robot)"""
    port: int = 8080
    """port for --view; the next free one if it is taken"""
    quiet: bool = False
    """print the result only, no progress"""


def _check_trial(cmd: TrialCommand | TeleopCommand) -> None:
    check_seed(cmd.seed)
    if not (math.isfinite(cmd.timeout_s) and cmd.timeout_s > 0):
        raise ConfigurationError(
            f"--timeout-s {cmd.timeout_s}: give the trial a positive simulated time (s)."
        )
    if not (math.isfinite(cmd.delay_ms) and cmd.delay_ms >= 0):
        raise ConfigurationError(f"--delay-ms {cmd.delay_ms}: give a delay of 0 ms or more.")
    if 2 * cmd.delay_ms / 1000 >= cmd.timeout_s:  # the operator sees a response a round trip on
        raise ConfigurationError(
            f"--delay-ms {cmd.delay_ms:g}: the operator would see the robot respond "
            f"{2 * cmd.delay_ms / 1000:g} s after moving (the round trip), after --timeout-s "
            f"{cmd.timeout_s:g} s; no trial can finish. Shorten the delay or lengthen the timeout."
        )
    if isinstance(cmd, TeleopCommand) or cmd.view:
        from arteleop.ar_features.host import check_host, check_port

        check_port(cmd.port)  # a taken one is not refused: the view moves on to the next
        check_host(cmd.host)
    from arteleop.operator import check_operator

    check_operator(cmd.operator, live=isinstance(cmd, TeleopCommand))


def _operator_options(cmd: TrialCommand) -> tuple[OperatorTraits, HandFilterConfig]:
    """The synthetic operator's traits and the hand filter from the options; one out of range
    is refused naming the option and its range."""
    from arteleop.operator import OperatorTraits
    from arteleop.teleop import HandFilterConfig

    options = {
        "confidence": "--confidence",
        "placement_criterion_m": "--placement-criterion-m",
        "min_cutoff_hz": "--filter-min-cutoff-hz",
        "beta_per_m": "--filter-beta",
    }
    try:
        traits = OperatorTraits(
            confidence=cmd.confidence, placement_criterion_m=cmd.placement_criterion_m
        )
        hand_filter = HandFilterConfig(
            enabled=not cmd.no_filter, min_cutoff_hz=cmd.filter_min_cutoff_hz,
            beta_per_m=cmd.filter_beta,
        )  # fmt: skip
    except ConfigurationError as err:
        name_value, expected = str(err).split(": expected ", 1)
        name, value = name_value.split(" = ", 1)
        option = options[name.rsplit(".", 1)[-1]]
        raise ConfigurationError(f"{option} {value}: expected {expected}") from None
    return traits, hand_filter


def trial(cmd: TrialCommand) -> int:
    _check_trial(cmd)  # before the imports that load the simulator: seconds on a cold disk
    from arteleop.ar_features import OperatorView, ViewConfig
    from arteleop.operator import RecordingSource, load_recording
    from arteleop.scene import RemoteSite, SiteConfig
    from arteleop.teleop import (
        POINTING,
        ControllerConfig,
        NetworkConfig,
        TrialConfig,
        run_trial,
        trial_operator,
        trial_task,
        view_assets,
    )

    try:
        trial_task(cmd.task)
    except ConfigurationError as err:  # named as the option it came from
        raise ConfigurationError(str(err).replace("task = ", "--task ", 1)) from None
    if cmd.task == POINTING.name:  # its start and target are a pointing design's, not a trial's
        raise ConfigurationError(
            "--task pointing: a pointing trial's targets come from a pointing study's design; "
            "run one with 'arteleop study run docs/examples/fitts_lag.toml --out DIR', or a study "
            'file of your own with task = "pointing".'
        )
    traits, hand_filter = _operator_options(cmd)
    config = TrialConfig(
        modality=cmd.modality, seed=cmd.seed, timeout_s=cmd.timeout_s,
        realtime=cmd.realtime or cmd.view, render_camera=cmd.view,
        network=NetworkConfig(delay_s=cmd.delay_ms / 1000),
        controller=ControllerConfig(hand_filter=hand_filter),
        site=SiteConfig(camera=cmd.camera_config()), depth_aids=cmd.depth_aids, task=cmd.task,
    )  # fmt: skip
    with contextlib.ExitStack() as stack:
        site = stack.enter_context(RemoteSite(config.site))
        if cmd.operator == "synthetic":
            source = trial_operator(site, config, traits=traits)
        else:
            source = RecordingSource(load_recording(Path(cmd.operator)))
        display = None
        if cmd.view:
            view_config = ViewConfig(host=cmd.host, port=cmd.port)
            display = stack.enter_context(OperatorView(view_config, view_assets(site)))
            for notice in display.notices():
                print(notice, file=sys.stderr)
            print(f"operator's view at {display.url}")
        with trial_progress(config.timeout_s, "trial", cmd.quiet) as progress:
            result = run_trial(source, config, site, display, progress)
        _print_trial(result)
        if display is not None and not cmd.exit_when_done:
            print(f"the trial is over; {display.url} shows its last frame until Ctrl-C")
            with contextlib.suppress(KeyboardInterrupt):
                while True:
                    time.sleep(1.0)
    return 0 if result.placed else 1


def _print_trial(result: TrialResult) -> None:
    import numpy as np

    print(f"outcome              {result.outcome.value}")
    print(f"grasped, placed      {result.grasped}, {result.placed}")
    print(f"completion time      {result.completion_time_s:.2f} s")
    print(f"placement error      {result.placement_error_m * 1000:.1f} mm (tracked), "
          f"{result.placement_error_true_m * 1000:.1f} mm (ground truth)")  # fmt: skip
    print(f"simulated time       {result.duration_s:.1f} s")
    row = result.to_row()
    if row["colocation_error_px"] > 0:  # a registration error was given
        print(f"co-location          {row['colocation_error_px']:.1f} px, "
              f"{row['colocation_error_m'] * 1000:.1f} mm (median: the ghost's gripper from the "
              "real one in the image)")  # fmt: skip
    if len(result.latency_wall_ms):
        lat = result.latency_wall_ms
        print(f"latency to display   {np.median(lat):.1f} ms median, "
              f"{np.percentile(lat, 95):.1f} ms p95 (sample to the view's update)")  # fmt: skip


@dataclass(frozen=True)
class TeleopCommand:
    """Teleoperate the simulated Baxter in real time in the browser, trial after trial."""

    operator: str = "synthetic"
    """'synthetic' (a new simulated participant each trial), 'live' (drive the gripper with a gizmo and a grip slider in the page), or the path of a wearable recording's CSV"""
    modality: Modality = "full"
    """AR modality of the trials (docs/explanation/study.md §3; 'predictive': the predictive ghost, ahead of a delayed view); the page's panel can switch layers live"""
    seed: int = 0
    """seed of the first trial (0 or more); each next trial takes the next one"""
    delay_ms: float = 0.0
    """one-way network delay between operator and robot (ms): the view shows each camera frame this long after it was taken, and the predictive ghost where the commands sent will put the arm"""
    timeout_s: float = 120.0
    """simulated time after which a trial ends as a timeout (s)"""
    depth_aids: bool = False
    """draw the depth aids: a line from the gripper straight down to the table, a ring at its foot and the gripper's height (what a flat screen cannot show; the simulated participant judges them too)"""
    width_px: int = 640
    """camera image width (px); the Kinect's 640x480 shows 30 frames/s, 47 ms from a sample to the view with OpenGL on two idle cores (fewer frames on a loaded machine, where 320x240 keeps 30 frames/s, 27 ms)"""
    height_px: int = 480
    """camera image height (px)"""
    renderer: Renderer = "auto"
    """what draws the head camera: 'gl' (OpenGL through EGL, on the CPU or a GPU), 'tiny' (PyBullet's TinyRenderer, several times slower), 'auto' (gl where it opens, else tiny)"""
    camera_offset_mm: tuple[float, float, float] = (0.0, 0.0, 0.0)
    """a mis-registered camera: its pose as the system uses it, moved by this (mm, camera frame), so the cloud sits off the ghost and the target (see 'arteleop trial --help')"""
    camera_offset_deg: tuple[float, float, float] = (0.0, 0.0, 0.0)
    """the registration's rotation error, a rotation vector (deg, camera frame)"""
    camera_graph: Path | None = None
    """a transform graph file (from 'arteleop calibrate') whose base -> head_camera edge is the camera's pose as the system uses it, instead of --camera-offset-*"""
    host: str = "127.0.0.1"
    """interface to serve the page on; 0.0.0.0 lets other machines connect (and drive the robot)"""
    port: int = 8080
    """port to serve the page on; the next free one if it is taken"""


def teleop(cmd: TeleopCommand) -> int:
    _check_trial(cmd)  # before the imports that load the simulator: seconds on a cold disk
    from arteleop.ar_features import ViewConfig
    from arteleop.scene import RemoteSite, SiteConfig
    from arteleop.teleop import NetworkConfig, TeleopApp, TeleopAppConfig, TrialConfig
    from arteleop.teleop.live_app import trial_summary

    size = CameraSize(cmd.width_px, cmd.height_px, cmd.renderer, cmd.camera_offset_mm,
                      cmd.camera_offset_deg, cmd.camera_graph)  # fmt: skip
    camera = size.camera_config()
    trial_config = TrialConfig(
        modality=cmd.modality, seed=cmd.seed, timeout_s=cmd.timeout_s,
        network=NetworkConfig(delay_s=cmd.delay_ms / 1000), site=SiteConfig(camera=camera),
        depth_aids=cmd.depth_aids,
    )  # fmt: skip
    config = TeleopAppConfig(cmd.operator, trial_config, ViewConfig(host=cmd.host, port=cmd.port))
    with RemoteSite(trial_config.site) as site, TeleopApp(config, site) as app:
        for notice in app.view.notices():
            print(notice, file=sys.stderr)
        print(f"operator's view at {app.view.url} (Ctrl-C stops)")

        def report(result: TrialResult) -> None:
            state, summary = trial_summary(result)
            print(f"trial {len(app.results)}: {state}; {summary}")

        app.run(report)
    return 0

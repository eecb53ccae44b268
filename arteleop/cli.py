"""The `arteleop` command. Each subcommand's options map one-to-one onto a config dataclass."""

from __future__ import annotations

import contextlib
import math
import os
import signal
import sys
import threading
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Any, Literal

import tyro

from arteleop.errors import ArteleopError, ConfigurationError, FrameGraphError

if TYPE_CHECKING:
    from arteleop.scene import HeadCameraConfig
    from arteleop.teleop import TrialProgress, TrialResult


Modality = Literal["none", "manipulation", "embodiment", "task", "full"]
"""The AR modalities (docs/study.md §3), as the command line offers them."""


def _check_seed(seed: int) -> None:
    if seed < 0:
        raise ConfigurationError(f"--seed {seed}: a seed is a whole number, 0 or more.")


@dataclass(frozen=True)
class CameraSize:
    """The head camera's image size, shared by the commands that render it."""

    width_px: int = 640
    """camera image width (px); 320x240 keeps 30 frames/s in real time on two cores"""
    height_px: int = 480
    """camera image height (px)"""
    camera_offset_mm: tuple[float, float, float] = (0.0, 0.0, 0.0)
    """a mis-registered camera: the pose the system uses for it (for the point cloud, the
    tracked bowl, the operator's eye) is the true one moved by this (mm, camera frame: x right,
    y down, z forward), while the ghost and the target stay where they are"""
    camera_offset_deg: tuple[float, float, float] = (0.0, 0.0, 0.0)
    """the registration's rotation error, a rotation vector (deg, camera frame)"""
    camera_graph: Path | None = None
    """a transform graph file (from 'arteleop calibrate') whose base -> head_camera edge is the
    camera's pose as the system uses it, instead of --camera-offset-*"""

    def camera_config(self, **overrides: Any) -> HeadCameraConfig:
        from arteleop.scene import BASE_FRAME, CAMERA_FRAME, HeadCameraConfig, TransformGraph

        registration: dict[str, Any] = {
            "registration_offset_mm": self.camera_offset_mm,
            "registration_offset_deg": self.camera_offset_deg,
        }
        if self.camera_graph is not None:
            if any(self.camera_offset_mm) or any(self.camera_offset_deg):
                raise ConfigurationError(
                    "--camera-graph and --camera-offset-mm/--camera-offset-deg: give one of them"
                )
            graph = TransformGraph.load(self.camera_graph)  # its errors name the file
            try:
                T = graph.T(BASE_FRAME, CAMERA_FRAME)
            except FrameGraphError as err:
                raise FrameGraphError(
                    f"--camera-graph {self.camera_graph}: {err}. 'arteleop calibrate' writes "
                    "such a file, with the edge base -> head_camera."
                ) from None
            registration = {"registered_pose": tuple(tuple(row) for row in T.tolist())}
        return HeadCameraConfig(
            width_px=self.width_px, height_px=self.height_px, **registration, **overrides
        )


@dataclass(frozen=True)
class SceneCommand(CameraSize):
    """Render one head-camera frame of the remote site at rest and track the bowl."""

    out: Annotated[
        Path,
        tyro.conf.arg(
            help="folder for rgb.png, depth.png (16-bit mm), depth_vis.png (false colour) and "
            "cloud.ply (base frame, m)"
        ),
    ] = field(default=Path("arteleop-scene"))
    seed: int = 0
    """seed of the depth noise (0 or more)"""
    noise: bool = True
    """add Kinect-like depth noise and quantisation"""


def scene(cmd: SceneCommand) -> int:
    from arteleop.scene import DepthNoiseConfig, RemoteSite, SiteConfig, write_snapshot

    _check_seed(cmd.seed)
    camera = cmd.camera_config(noise=DepthNoiseConfig(enabled=cmd.noise, quantize=cmd.noise))
    with RemoteSite(SiteConfig(camera=camera, seed=cmd.seed)) as site:
        snap = write_snapshot(site, cmd.out)
    for name, path in snap.files.items():
        print(f"wrote {name:9s} {path}")
    truth = snap.bowl_true_m
    print(
        f"bowl (ground truth)  x={truth[0]:+.4f} y={truth[1]:+.4f} z={truth[2]:+.4f} m (base frame)"
    )
    if not snap.track.found or snap.track.position_m is None:
        print(f"bowl not found: {snap.track.reason}")
        return 1
    est = snap.track.position_m
    print(
        f"bowl (tracked)      x={est[0]:+.4f} y={est[1]:+.4f} z={est[2]:+.4f} m "
        f"from {snap.track.n_points} points"
    )
    print(f"tracking error      {snap.tracking_error_m * 1000:.1f} mm")
    return 0


CalibrationMethod = Literal["best", "tsai", "park", "horaud", "andreff", "daniilidis", "shah", "li"]


@dataclass(frozen=True)
class CalibrateCommand(CameraSize):
    """Register the head camera to the robot, in simulation, with the camera's true pose hidden
    from the solvers: a marker on the table (helper-based) and a board in the gripper shown in
    --poses poses (hand-eye: seven OpenCV methods, the best refined on the marker's corners).
    Prints each estimate's error against the true pose, its reprojection error and the ghost's
    co-location error, and writes the refined estimate, with its covariance, into a transform
    graph file."""

    poses: int = 10
    """hand-eye: poses with the board in view (3 or more)"""
    seed: int = 0
    """seed of the poses and of the marker's placements (0 or more)"""
    method: CalibrationMethod = "best"
    """the closed-form hand-eye estimate that starts the refinement written to --out; 'best' is
    the one with the lowest reprojection error (which needs no ground truth)"""
    out: Path = Path("calibration.json")
    """transform graph file (JSON) to write: the site's frames (the robot's links at rest, the
    table, the markers) and the camera's, joined to base by an edge of kind calibration"""


def calibrate(cmd: CalibrateCommand) -> int:
    import numpy as np

    from arteleop.scene import (
        BASE_FRAME,
        CAMERA_FRAME,
        CalibrationConfig,
        EdgeKind,
        RemoteSite,
        SiteConfig,
        calibrate_camera,
        calibration_errors,
    )

    _check_seed(cmd.seed)
    config = CalibrationConfig(poses=cmd.poses, seed=cmd.seed)
    with RemoteSite(SiteConfig(camera=cmd.camera_config(), seed=cmd.seed)) as site:
        run = calibrate_camera(site, config, cmd.method)
        T_true = site.camera.T_base_camera
        registered = site.camera.registered.T_base_camera
        intrinsics = site.camera.intrinsics
        graph = site.frames.graph  # the robot at rest, the table, the markers, the camera
    chosen = run.refined
    positions = run.data.T_base_gripper[:, :3, 3]
    print(
        f"hand-eye: {len(positions)} usable poses of {run.data.attempts} tried; helper: "
        f"{run.helper.poses} sightings of the table marker\n"
    )
    print(
        "| method | poses | error (mm) | error (deg) | reprojection (px) "
        "| co-location (px) | co-location (mm) |"
    )
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: |")
    if not np.array_equal(registered, T_true):
        e = calibration_errors(registered, T_true, intrinsics, positions)
        print(
            f"| registration given (--camera-offset-*) | - | {e.error_mm:.1f} | {e.error_deg:.2f} "
            f"| - | {e.colocation_px:.1f} | {e.colocation_mm:.1f} |"
        )
    for r in [run.helper, *run.closed_form, chosen]:
        e = calibration_errors(r.T_base_camera, T_true, intrinsics, positions)
        print(
            f"| {r.method} | {r.poses} | {e.error_mm:.1f} | {e.error_deg:.2f} "
            f"| {r.reprojection_error_px:.2f} | {e.colocation_px:.1f} | {e.colocation_mm:.1f} |"
        )
    graph.set(BASE_FRAME, CAMERA_FRAME, chosen.transform, EdgeKind.CALIBRATION)
    graph.save(cmd.out)
    print(
        f"\nwrote {cmd.out}: the site's frames, with base -> head_camera from {chosen.method} "
        "(co-location is measured at the hand-eye poses' gripper positions)"
    )
    return 0


@dataclass(frozen=True)
class OperatorCheckCommand:
    """Validate a wearable recording and summarise it; exit non-zero if it is invalid."""

    file: tyro.conf.Positional[Path]
    """the recording's CSV; its JSON sidecar sits beside it with the same stem"""


def operator_check(cmd: OperatorCheckCommand) -> int:
    from arteleop.analysis import path_length
    from arteleop.operator import load_recording, reconstruct

    rec = load_recording(cmd.file)
    traj = reconstruct(rec)
    measured_hz = (len(rec.time_s) - 1) / rec.duration_s
    report = rec.report
    print(f"recording     {cmd.file} (subject {rec.info.subject_id})")
    print(f"duration      {rec.duration_s:.2f} s, {len(rec.time_s)} samples")
    print(
        f"rate          {rec.info.rate_hz:g} Hz in the sidecar, {measured_hz:.2f} Hz after filling"
    )
    print(f"gaps          {report.gaps} filled by slerp ({report.filled_samples} samples)")
    print(
        f"lost          {report.lost_samples} samples marked lost by the wearable (filled "
        "for this summary; a replay loses them again)"
    )
    print(f"renormalised  {report.renormalized} quaternions")
    length = path_length(traj.time_s, traj.hand_m)
    print(
        f"hand path     {length:.3f} m (reconstructed pinch point, torso frame, low-pass "
        "filtered at 6 Hz as the analysis does: summed raw, sensor noise adds metres)"
    )
    return 0


@dataclass(frozen=True)
class AnalyzeCommand:
    """Analyse a study's files (docs/study.md §5) and write tables, figures and report.md."""

    source: tyro.conf.Positional[Path]
    """run folder (trials.csv, participants.csv, questionnaire.csv, trajectories/) or trials CSV"""
    out: Path = Path("arteleop-report")
    """report folder"""
    participants: Path | None = None
    """participants.csv for a bare trials CSV"""
    trim: bool = True
    """drop each group's maximum and minimum participant (the thesis)"""
    paired: bool = False
    """within-subject tests (paired t-test / Wilcoxon) between modalities"""
    holm: bool = False
    """Holm-correct each family of pairwise tests"""


def analyze(cmd: AnalyzeCommand) -> int:
    from arteleop.analysis import (
        AnalysisInputError,
        AnalysisOptions,
        analyse,
        load_study,
        write_report,
    )

    try:
        study = load_study(cmd.source, cmd.participants)
        options = AnalysisOptions(trim=cmd.trim, paired=cmd.paired, holm=cmd.holm)
        result = analyse(study, options)
        files = write_report(study, result, options, cmd.out)
    except AnalysisInputError as err:
        print(f"arteleop: error: {err}", file=sys.stderr)
        return 2
    n_people = result.trials["participant"].nunique()
    print(f"analysed {result.counts['analysed']} trials of {n_people} participants")
    significant = result.tests[(result.tests["stars"] != "") & result.tests["stars"].notna()]
    print(f"{len(result.tests)} tests, {len(significant)} significant at p <= 0.05")
    for note in result.notes:
        print(f"note: {note}")
    print(f"wrote {len(files)} files to {cmd.out}, see {files['report.md']}")
    return 0


@dataclass(frozen=True)
class TrialCommand(CameraSize):
    """Run one pick-and-place trial and print its outcome; headless unless --view."""

    operator: str = "synthetic"
    """'synthetic' (a simulated participant), or the path of a wearable recording's CSV"""
    modality: Modality = "full"
    """AR modality shown to the operator (docs/study.md §3)"""
    seed: int = 0
    """seed of every random source of the trial (0 or more)"""
    delay_ms: float = 0.0
    """one-way network delay between operator and robot (ms)"""
    timeout_s: float = 120.0
    """simulated time after which the trial ends as a timeout (s)"""
    realtime: bool = False
    """pace the loop with the wall clock"""
    view: bool = False
    """serve the operator's view (point cloud and AR layers) in the browser, in real time"""
    exit_when_done: bool = False
    """with --view: stop when the trial ends (else the view keeps its last frame until Ctrl-C)"""
    host: str = "127.0.0.1"
    """interface for --view; 0.0.0.0 lets other machines connect (and drive the robot)"""
    port: int = 8080
    """port for --view; the next free one if it is taken"""
    quiet: bool = False
    """print the result only, no progress"""


def _check_trial(cmd: TrialCommand | TeleopCommand) -> None:
    _check_seed(cmd.seed)
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
    from arteleop.operator import check_operator

    check_operator(cmd.operator, live=isinstance(cmd, TeleopCommand))


def trial(cmd: TrialCommand) -> int:

    from arteleop.ar_features import OperatorView, ViewConfig
    from arteleop.operator import RecordingSource, load_recording
    from arteleop.scene import RemoteSite, SiteConfig
    from arteleop.teleop import NetworkConfig, TrialConfig, run_trial, trial_operator, view_assets

    _check_trial(cmd)
    config = TrialConfig(
        modality=cmd.modality, seed=cmd.seed, timeout_s=cmd.timeout_s,
        realtime=cmd.realtime or cmd.view, render_camera=cmd.view,
        network=NetworkConfig(delay_s=cmd.delay_ms / 1000),
        site=SiteConfig(camera=cmd.camera_config()),
    )  # fmt: skip
    with contextlib.ExitStack() as stack:
        site = stack.enter_context(RemoteSite(config.site))
        if cmd.operator == "synthetic":
            source = trial_operator(site, config)
        else:
            source = RecordingSource(load_recording(Path(cmd.operator)))
        display = None
        if cmd.view:
            view_config = ViewConfig(host=cmd.host, port=cmd.port)
            display = stack.enter_context(OperatorView(view_config, view_assets(site)))
            for notice in display.notices():
                print(notice, file=sys.stderr)
            print(f"operator's view at {display.url}")
        with _progress(config.timeout_s, "trial", cmd.quiet) as progress:
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
class OperatorSynthCommand:
    """Run one synthetic trial headless and write the operator's wearable recording."""

    modality: Modality = "full"
    """AR modality shown to the synthetic operator (docs/study.md §3)"""
    seed: int = 0
    """seed of every random source of the trial (0 or more)"""
    out: Path = Path("synthetic.csv")
    """recording CSV (its JSON sidecar is written beside it)"""
    quiet: bool = False
    """print the result only, no progress"""


def operator_synth(cmd: OperatorSynthCommand) -> int:
    from arteleop.operator import sidecar_path, write_recording
    from arteleop.scene import RemoteSite
    from arteleop.teleop import TrialConfig, run_trial, trial_operator

    _check_seed(cmd.seed)
    config = TrialConfig(modality=cmd.modality, seed=cmd.seed)
    with RemoteSite(config.site) as site:
        source = trial_operator(site, config)
        with _progress(config.timeout_s, "trial", cmd.quiet) as progress:
            result = run_trial(source, config, site, progress=progress)
    rec = source.recording(subject_id=f"synthetic-{cmd.modality}-{cmd.seed}")
    write_recording(rec, cmd.out)
    print(f"trial outcome {result.outcome.value}")
    print(f"wrote {cmd.out} and its sidecar {sidecar_path(cmd.out)}")
    print(
        f"{len(rec.time_s)} samples at {rec.info.rate_hz:g} Hz, {int(rec.lost.sum())} of them "
        "lost by the wearable in flight (rows with the time only, lost again on replay)"
    )
    return 0


@contextlib.contextmanager
def _progress(
    total_s: float, what: str, quiet: bool
) -> Iterator[Callable[[TrialProgress], None] | None]:
    """A progress bar over simulated seconds, on stderr; nothing with --quiet."""
    if quiet:
        yield _check_ctrl_c
        return
    from tqdm import tqdm

    with tqdm(total=round(total_s), desc=what, unit="s simulated", leave=False) as bar:

        def update(status: TrialProgress) -> None:
            _check_ctrl_c()
            if int(status.time_s) > bar.n:
                bar.update(int(status.time_s) - bar.n)

        yield update


@dataclass(frozen=True)
class TeleopCommand:
    """Teleoperate the simulated Baxter in real time in the browser, trial after trial."""

    operator: str = "synthetic"
    """'synthetic' (a new simulated participant each trial), 'live' (drive the gripper with a
    gizmo and a grip slider in the page), or the path of a wearable recording's CSV"""
    modality: Modality = "full"
    """AR modality of the trials (docs/study.md §3); the page's panel can switch layers live"""
    seed: int = 0
    """seed of the first trial (0 or more); each next trial takes the next one"""
    delay_ms: float = 0.0
    """one-way network delay between operator and robot (ms)"""
    timeout_s: float = 120.0
    """simulated time after which a trial ends as a timeout (s)"""
    width_px: int = 320
    """camera image width (px); 320x240 keeps 30 frames/s in real time on two cores"""
    height_px: int = 240
    """camera image height (px)"""
    camera_offset_mm: tuple[float, float, float] = (0.0, 0.0, 0.0)
    """a mis-registered camera: its pose as the system uses it, moved by this (mm, camera
    frame), so the cloud sits off the ghost and the target (see 'arteleop trial --help')"""
    camera_offset_deg: tuple[float, float, float] = (0.0, 0.0, 0.0)
    """the registration's rotation error, a rotation vector (deg, camera frame)"""
    camera_graph: Path | None = None
    """a transform graph file (from 'arteleop calibrate') whose base -> head_camera edge is the
    camera's pose as the system uses it, instead of --camera-offset-*"""
    host: str = "127.0.0.1"
    """interface to serve the page on; 0.0.0.0 lets other machines connect (and drive the robot)"""
    port: int = 8080
    """port to serve the page on; the next free one if it is taken"""


def teleop(cmd: TeleopCommand) -> int:
    from arteleop.ar_features import ViewConfig
    from arteleop.scene import RemoteSite, SiteConfig
    from arteleop.teleop import NetworkConfig, TeleopApp, TeleopAppConfig, TrialConfig
    from arteleop.teleop.live_app import trial_summary

    _check_trial(cmd)
    size = CameraSize(
        cmd.width_px, cmd.height_px, cmd.camera_offset_mm, cmd.camera_offset_deg, cmd.camera_graph
    )
    camera = size.camera_config()
    trial_config = TrialConfig(
        modality=cmd.modality, seed=cmd.seed, timeout_s=cmd.timeout_s,
        network=NetworkConfig(delay_s=cmd.delay_ms / 1000), site=SiteConfig(camera=camera),
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


@dataclass(frozen=True)
class StudyInitCommand:
    """Write the default study definition, commented, for you to edit."""

    file: tyro.conf.Positional[Path]
    """the TOML file to write (refused if it exists)"""


def study_init(cmd: StudyInitCommand) -> int:
    from arteleop.study import StudyConfig, study_text

    if cmd.file.exists():
        raise ConfigurationError(f"{cmd.file} exists; give a new file name (nothing was written).")
    try:
        cmd.file.write_text(study_text(StudyConfig()), encoding="utf-8")
    except OSError as err:
        raise ConfigurationError(f"Cannot write {cmd.file}: {err.strerror or err}.") from err
    print(f"wrote {cmd.file}: the default study (docs/study.md §4); edit it, then")
    print(f"  arteleop study run {cmd.file} --out RUN_DIR")
    return 0


@dataclass(frozen=True)
class StudyRunCommand:
    """Run a study (the built-in default without a file), then analyse it into RUN_DIR/report."""

    file: Annotated[tyro.conf.Positional[Path | None], tyro.conf.arg(metavar="[STUDY.toml]")] = None
    """the study definition ('arteleop study init FILE' writes one); none: the default"""
    out: Path = Path("arteleop-study")
    """the run folder to create (must be new or empty)"""
    workers: int = 0
    """processes running trials; 0: one per core"""
    quiet: bool = False
    """print the summary only, no progress"""


@dataclass(frozen=True)
class StudyResumeCommand:
    """Continue a run folder after a crash, Ctrl-C or kill; then analyse it."""

    run_dir: Annotated[tyro.conf.Positional[Path], tyro.conf.arg(metavar="RUN_DIR")]
    """the run folder that 'arteleop study run' began"""
    workers: int = 0
    """processes running trials; 0: one per core"""
    quiet: bool = False
    """print the summary only, no progress"""


def study_run(cmd: StudyRunCommand) -> int:
    from arteleop.study import StudyConfig, load_study_file, run_study

    _check_workers(cmd.workers)
    study = StudyConfig() if cmd.file is None else load_study_file(cmd.file)[0]
    with _study_progress(cmd.out, cmd.quiet) as progress:
        run = run_study(study, cmd.out, cmd.workers or None, progress=progress)
    return _study_done(run)


def study_resume(cmd: StudyResumeCommand) -> int:
    from arteleop.study import RunComplete, resume_study

    _check_workers(cmd.workers)
    try:
        with _study_progress(cmd.run_dir, cmd.quiet) as progress:
            run = resume_study(cmd.run_dir, workers=cmd.workers or None, progress=progress)
    except RunComplete as done:
        print(done)
        return 0
    return _study_done(run)


def _check_workers(workers: int) -> None:
    if workers < 0:
        raise ConfigurationError(f"--workers {workers}: give 1 or more, or 0 for one per core.")


@contextlib.contextmanager
def _study_progress(run_dir: Path, quiet: bool) -> Iterator[Any]:
    """A progress bar over the study's trials, with the participant of the last one; the hint
    to resume on Ctrl-C."""
    from tqdm import tqdm

    bars: list[tqdm] = []  # made at the first trial, after the definition has been checked

    def update(spec: Any, done: int, total: int) -> None:
        _check_ctrl_c()
        if quiet:
            return
        if not bars:
            bars.append(tqdm(desc="trials", unit="trial", total=total, initial=done - 1,
                             leave=False))  # fmt: skip
        bars[0].update(done - bars[0].n)
        bars[0].set_postfix_str(f"last: {spec.participant} trial {spec.trial_index}")

    try:
        yield update
    except KeyboardInterrupt:
        raise KeyboardInterrupt(f"'arteleop study resume {run_dir}' continues the run") from None
    finally:
        for bar in bars:
            bar.close()


def _study_done(run: Any) -> int:
    trials = run.trials
    experimental = trials[trials["phase"] == "experimental"]
    print(f"{len(trials)} trials in {run.folder} ({run.ran} run now)")
    print("outcomes: " + ", ".join(f"{k} {v}" for k, v in trials["outcome"].value_counts().items()))
    print(f"{'modality':<14}{'trials':>7}{'success':>9}{'median time (s)':>17}"
          f"{'median error (mm)':>19}")  # fmt: skip
    for modality, group in experimental.groupby("modality", sort=False):
        ok = group[group["outcome"] == "success"]
        print(f"{modality:<14}{len(group):>7}{len(ok):>9}"
              f"{ok['completion_time_s'].median():>17.1f}"
              f"{1000 * ok['placement_error_m'].median():>19.1f}")  # fmt: skip
    return analyze(AnalyzeCommand(source=run.folder, out=run.folder / "report"))


@dataclass(frozen=True)
class StudyAnswerCommand:
    """Merge real questionnaire answers into a run folder's questionnaire.csv."""

    run_dir: Annotated[tyro.conf.Positional[Path], tyro.conf.arg(metavar="RUN_DIR")]
    """the run folder"""
    answers: Annotated[tyro.conf.Positional[Path], tyro.conf.arg(metavar="ANSWERS.csv")]
    """CSV with participant, ar_class, item, score (docs/data-format.md); these participants'
    answers replace the simulated ones"""


def study_answer(cmd: StudyAnswerCommand) -> int:
    from arteleop.study.answers import merge_answers

    replaced = merge_answers(cmd.run_dir, cmd.answers)
    print(f"merged answers of {len(replaced)} participants into {cmd.run_dir}/questionnaire.csv: "
          f"{', '.join(replaced)}")  # fmt: skip
    print(f"analyse again: arteleop analyze {cmd.run_dir} --out {cmd.run_dir / 'report'}")
    return 0


@dataclass(frozen=True)
class StudyReplayCommand(CameraSize):
    """Play a trial of a run folder back in the operator's view, with its modality's layers."""

    run_dir: Annotated[tyro.conf.Positional[Path], tyro.conf.arg(metavar="RUN_DIR")] = Path(
        "arteleop-study"
    )
    """the run folder"""
    participant: Annotated[tyro.conf.Positional[str], tyro.conf.arg(metavar="PARTICIPANT")] = "P01"
    """the participant's id, as in trials.csv"""
    trial: Annotated[tyro.conf.Positional[int], tyro.conf.arg(metavar="TRIAL")] = 1
    """the trial's index in the participant's session (trial_index in trials.csv)"""
    speed: float = 1.0
    """times real time; 0 plays as fast as the camera renders"""
    width_px: int = 320
    """camera image width (px); 320x240 keeps 30 frames/s on two cores"""
    height_px: int = 240
    """camera image height (px)"""
    camera_offset_mm: tuple[float, float, float] = (0.0, 0.0, 0.0)
    """a mis-registered camera: its pose as the system uses it, moved by this (mm, camera
    frame), so the cloud sits off the ghost and the target (see 'arteleop trial --help')"""
    camera_offset_deg: tuple[float, float, float] = (0.0, 0.0, 0.0)
    """the registration's rotation error, a rotation vector (deg, camera frame)"""
    host: str = "127.0.0.1"
    """interface to serve the page on; 0.0.0.0 lets other machines connect"""
    port: int = 8080
    """port to serve the page on; the next free one if it is taken"""
    exit_when_done: bool = False
    """stop when the trial has played (else the view keeps its last frame until Ctrl-C)"""


def study_replay(cmd: StudyReplayCommand) -> int:
    from arteleop.ar_features import OperatorView, ViewConfig
    from arteleop.scene import RemoteSite
    from arteleop.study.replay import load_replay, replay, replay_site
    from arteleop.teleop import view_assets

    source = load_replay(cmd.run_dir, cmd.participant, cmd.trial)
    with (
        RemoteSite(replay_site(source, cmd.camera_config())) as site,
        OperatorView(ViewConfig(host=cmd.host, port=cmd.port), view_assets(site)) as view,
    ):
        for notice in view.notices():
            print(notice, file=sys.stderr)
        spec = source.spec
        print(f"replaying {cmd.participant} trial {cmd.trial} ({spec.phase}, {source.modality}, "
              f"{source.outcome}) at {view.url}")  # fmt: skip
        frames = replay(source, site, view, cmd.speed)
        print(f"played {frames} frames")
        if not cmd.exit_when_done:
            print(f"{view.url} shows the last frame until Ctrl-C")
            with contextlib.suppress(KeyboardInterrupt):
                while True:
                    time.sleep(1.0)
    return 0


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
        "answer": (StudyAnswerCommand, study_answer),
        "replay": (StudyReplayCommand, study_replay),
    },
}
OVERVIEW = """\
arteleop: study Augmented Reality in robot teleoperation, in simulation (docs/study.md).

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
  analyze          the study's statistics, figures and report from its CSV files

'arteleop COMMAND --help' lists a command's options."""


_CTRL_C = threading.Event()
"""Set by the first Ctrl-C. Some libraries turn a KeyboardInterrupt raised while they import into
an ImportError (open3d: "initialization failed"), and some swallow that in an optional-import
guard; the command still ends as interrupted."""


def _on_ctrl_c(signum: int, frame: object) -> None:
    _CTRL_C.set()
    raise KeyboardInterrupt


def _check_ctrl_c(*_: object) -> None:
    """Raise KeyboardInterrupt if a Ctrl-C came and was swallowed on its way up."""
    if _CTRL_C.is_set():
        raise KeyboardInterrupt


def main(argv: list[str] | None = None) -> int:
    """Entry point of the `arteleop` command."""
    argv = sys.argv[1:] if argv is None else list(argv)
    if (
        threading.current_thread() is threading.main_thread()
        and signal.getsignal(signal.SIGINT) is signal.default_int_handler
    ):
        signal.signal(signal.SIGINT, _on_ctrl_c)
    if not argv or argv[0] in ("-h", "--help"):
        print(OVERVIEW, file=sys.stdout if argv else sys.stderr)
        return 0 if argv else 2
    if argv[0] in GROUPS:
        commands, prog, args = GROUPS[argv[0]], f"arteleop {argv[0]}", argv[1:]
    else:
        commands, prog, args = COMMANDS, "arteleop", argv
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
        if _CTRL_C.is_set():  # interrupted while importing: nothing of the user's is pending
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


if __name__ == "__main__":
    sys.exit(main())

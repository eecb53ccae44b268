"""The `arteleop` command. Each subcommand's options map one-to-one onto a config dataclass."""

from __future__ import annotations

import contextlib
import sys
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Any

import tyro

from arteleop.errors import ArteleopError

if TYPE_CHECKING:
    from arteleop.operator import SyntheticSource
    from arteleop.scene import HeadCameraConfig, RemoteSite
    from arteleop.teleop import TrialConfig


@dataclass(frozen=True)
class CameraSize:
    """The head camera's image size, shared by the commands that render it."""

    width_px: int = 640
    """camera image width (px); 320x240 keeps 30 frames/s in real time on two cores"""
    height_px: int = 480
    """camera image height (px)"""

    def camera_config(self, **overrides: Any) -> HeadCameraConfig:
        from arteleop.scene import HeadCameraConfig

        return HeadCameraConfig(width_px=self.width_px, height_px=self.height_px, **overrides)


@dataclass(frozen=True)
class SceneCommand(CameraSize):
    """Render one head-camera frame of the remote site at rest and track the bowl."""

    out: Annotated[
        Path, tyro.conf.arg(help="folder for rgb.png, depth.png (16-bit mm) and cloud.ply")
    ] = field(default=Path("arteleop-scene"))
    seed: int = 0
    """seed of the depth noise"""
    noise: bool = True
    """add Kinect-like depth noise and quantisation"""


def scene(cmd: SceneCommand) -> int:
    from arteleop.scene import DepthNoiseConfig, RemoteSite, SiteConfig, write_snapshot

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


@dataclass(frozen=True)
class OperatorCheckCommand:
    """Validate a wearable recording and summarise it; exit non-zero if it is invalid."""

    file: tyro.conf.Positional[Path]
    """the recording's CSV; its JSON sidecar sits beside it with the same stem"""


def operator_check(cmd: OperatorCheckCommand) -> int:
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
    print(f"renormalised  {report.renormalized} quaternions")
    print(f"hand path     {traj.path_length_m():.3f} m (reconstructed pinch point, torso frame)")
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
    """'synthetic', or a wearable recording's CSV"""
    modality: str = "full"
    """none, manipulation, embodiment, task or full"""
    seed: int = 0
    delay_ms: float = 0.0
    """one-way network delay"""
    timeout_s: float = 120.0
    realtime: bool = False
    """pace the loop with the wall clock"""
    view: bool = False
    """serve the operator's view (point cloud and AR layers) in the browser, in real time"""
    host: str = "127.0.0.1"
    """interface for --view; 0.0.0.0 lets other machines connect"""
    port: int = 8080
    """port for --view"""


def trial(cmd: TrialCommand) -> int:
    import numpy as np

    from arteleop.ar_features import OperatorView, ViewConfig
    from arteleop.operator import RecordingSource, load_recording
    from arteleop.scene import RemoteSite, SiteConfig
    from arteleop.teleop import NetworkConfig, TrialConfig, run_trial, view_assets

    config = TrialConfig(
        modality=cmd.modality, seed=cmd.seed, timeout_s=cmd.timeout_s,
        realtime=cmd.realtime or cmd.view, render_camera=cmd.view,
        network=NetworkConfig(delay_s=cmd.delay_ms / 1000),
        site=SiteConfig(camera=cmd.camera_config()),
    )  # fmt: skip
    with contextlib.ExitStack() as stack:
        site = stack.enter_context(RemoteSite(config.site))
        if cmd.operator == "synthetic":
            source = _synthetic_source(site, config)
        else:
            source = RecordingSource(load_recording(Path(cmd.operator)))
        display = None
        if cmd.view:
            view_config = ViewConfig(host=cmd.host, port=cmd.port)
            display = stack.enter_context(OperatorView(view_config, view_assets(site)))
            print(f"operator's view at {display.url}")
        result = run_trial(source, config, site, display)
    print(f"outcome              {result.outcome.value}")
    print(f"grasped, placed      {result.grasped}, {result.placed}")
    print(f"completion time      {result.completion_time_s:.2f} s")
    print(f"placement error      {result.placement_error_m * 1000:.1f} mm (tracked), "
          f"{result.placement_error_true_m * 1000:.1f} mm (ground truth)")  # fmt: skip
    print(f"simulated time       {result.duration_s:.1f} s")
    if len(result.latency_wall_ms):
        lat = result.latency_wall_ms
        print(f"latency to display   {np.median(lat):.1f} ms median, "
              f"{np.percentile(lat, 95):.1f} ms p95 (sample to the view's update)")  # fmt: skip
    return 0 if result.placed else 1


@dataclass(frozen=True)
class OperatorSynthCommand:
    """Run one synthetic trial headless and write the operator's wearable recording."""

    modality: str = "full"
    """none, manipulation, embodiment, task or full"""
    seed: int = 0
    out: Path = Path("synthetic.csv")
    """recording CSV (its JSON sidecar is written beside it)"""


def operator_synth(cmd: OperatorSynthCommand) -> int:
    from arteleop.operator import Recording, RecordingInfo, write_recording
    from arteleop.scene import RemoteSite
    from arteleop.teleop import TrialConfig, run_trial

    config = TrialConfig(modality=cmd.modality, seed=cmd.seed)
    with RemoteSite(config.site) as site:
        source = _synthetic_source(site, config)
        result = run_trial(source, config, site)
    rec = source.recorded()
    info = RecordingInfo(
        rate_hz=source.wearable.config.rate_hz,
        arm=source.arm,
        calibration=source.calibration,
        subject_id=f"synthetic-{cmd.modality}-{cmd.seed}",
    )
    write_recording(Recording(rec.time_s, rec.sensor_quat_wxyz, rec.grip, info), cmd.out)
    print(f"trial outcome {result.outcome.value}; wrote {len(rec.time_s)} samples to {cmd.out}")
    return 0


def _synthetic_source(site: RemoteSite, config: TrialConfig) -> SyntheticSource:
    """The synthetic operator of a trial on ``site``, seeded from the trial's seed."""
    from arteleop.operator import synthetic_source

    rest_gripper_m = site.observe().gripper_m
    ws = site.config.workspace
    return synthetic_source(ws.bowl, rest_gripper_m, config.controller.mapping, config.seed)


Command = tuple[type, Callable[[Any], int]]
COMMANDS: dict[str, Command] = {
    "scene": (SceneCommand, scene),
    "analyze": (AnalyzeCommand, analyze),
    "trial": (TrialCommand, trial),
}
GROUPS: dict[str, dict[str, Command]] = {
    "operator": {
        "check": (OperatorCheckCommand, operator_check),
        "synth": (OperatorSynthCommand, operator_synth),
    }
}
DESCRIPTION = (
    "arteleop: study Augmented Reality in robot teleoperation, in simulation. "
    "Command groups: 'arteleop operator check FILE.csv' validates a wearable recording; "
    "'arteleop operator synth --modality M --seed N --out FILE.csv' records a synthetic operator."
)


def main(argv: list[str] | None = None) -> int:
    """Entry point of the `arteleop` command."""
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv and argv[0] in GROUPS:
        commands, prog, args = GROUPS[argv[0]], f"arteleop {argv[0]}", argv[1:]
    else:
        commands, prog, args = COMMANDS, "arteleop", argv
    cmd = tyro.extras.subcommand_cli_from_dict(
        {name: cfg for name, (cfg, _) in commands.items()},
        prog=prog,
        args=args,
        description=DESCRIPTION,
    )
    run = next(fn for cfg, fn in commands.values() if isinstance(cmd, cfg))
    try:
        return run(cmd)
    except ArteleopError as err:
        print(f"arteleop: error: {err}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())

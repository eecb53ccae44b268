"""'arteleop study': init, run, resume, answer and replay."""

from __future__ import annotations

import contextlib
import sys
import time
from collections.abc import Iterator
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Annotated, Any

import tyro

from arteleop.cli.analyze import AnalyzeCommand, analyze
from arteleop.cli.interrupt import check_ctrl_c
from arteleop.cli.options import CameraSize, check_seed
from arteleop.errors import ConfigurationError, ReportWriteError


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
    print(f"wrote {cmd.file}: the default study (docs/explanation/study.md §4); edit it, then")
    print(f"  arteleop study run {cmd.file} --out RUN_DIR")
    return 0


@dataclass(frozen=True)
class StudyRunCommand:
    """Run a study (the built-in default without a file), then analyse it into RUN_DIR/report."""

    file: Annotated[tyro.conf.Positional[Path | None], tyro.conf.arg(metavar="[STUDY.toml]")] = None
    """the study definition ('arteleop study init FILE' writes one); none: the default"""
    out: Path = Path("arteleop-study")
    """the run folder to create (must be new or empty)"""
    seed: int | None = None
    """the study's seed (0 or more) instead of the definition's: another cohort, other orders and trials (the run folder's study.toml records it)"""
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
    if cmd.seed is not None:
        check_seed(cmd.seed)
        study = replace(study, seed=cmd.seed)
    with _study_progress(cmd.out, cmd.quiet) as progress:
        run = run_study(study, cmd.out, cmd.workers or None, progress=progress)
    return _study_done(run)


def study_resume(cmd: StudyResumeCommand) -> int:
    from arteleop.study import RunComplete, RunFolder, resume_study

    _check_workers(cmd.workers)
    try:
        with _study_progress(cmd.run_dir, cmd.quiet) as progress:
            run = resume_study(cmd.run_dir, workers=cmd.workers or None, progress=progress,
                               tell=lambda note: print(f"note: {note}"))  # fmt: skip
    except RunComplete as done:
        print(done)
        if RunFolder(cmd.run_dir).report_finished():
            return 0
        print("its report is not whole: writing it")
        return _write_run_report(cmd.run_dir)
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
    began_s = time.time()  # tqdm's clock

    def update(spec: Any, done: int, total: int) -> None:
        check_ctrl_c()
        if quiet:
            return
        if not bars:
            bar = tqdm(desc="trials", unit="trial", total=total, initial=done - 1, leave=False)
            # Timed from the run's start: made at the first trial's end, it would give that
            # trial no time, and the rate thousands of trials a second.
            bar.start_t = bar.last_print_t = began_s
            bars.append(bar)
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
    from arteleop.teleop import POINTING

    if run.task == POINTING.name:
        return _pointing_done(run)
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
    for note in run.notes:
        print(f"note: {note}")
    return _write_run_report(run.folder)


def _pointing_done(run: Any) -> int:
    trials = run.trials
    print(f"{len(trials)} pointing trials in {run.folder} ({run.ran} run now)")
    print(f"{'lag (ms)':>8}{'trials':>8}{'selected':>10}{'hits':>6}{'median MT (s)':>15}")
    for lag, group in trials.groupby("round_trip_ms"):
        selected = group["movement_time_s"].notna()
        print(f"{lag:>8g}{len(group):>8}{int(selected.sum()):>10}{int(group['hit'].sum()):>6}"
              f"{group['movement_time_s'].median():>15.2f}")  # fmt: skip
    for note in run.notes:
        print(f"note: {note}")
    return _write_run_report(run.folder)


def _write_run_report(folder: Path) -> int:
    """The run's analysis into RUN_DIR/report, whole, under the run's lock; the manifest says
    it is finished only once its last file is in."""
    from datetime import UTC, datetime

    from arteleop.study import RunFolder, run_lock

    report = folder / "report"
    resume = f"'arteleop study resume {folder}' writes it"
    with run_lock(folder):
        try:
            code = analyze(AnalyzeCommand(sources=(folder,), out=report, force=True))
        except KeyboardInterrupt:
            raise KeyboardInterrupt(f"the trials are all in {folder}; {resume}") from None
        except ReportWriteError as err:
            raise ReportWriteError(f"{err} The trials are all in {folder}; {resume}.") from None
        if code == 0:
            RunFolder(folder).mark_report_finished(datetime.now(UTC).isoformat(timespec="seconds"))
    return code


@dataclass(frozen=True)
class StudyServeCommand:
    """Serve a study to people in their browser, one participant after another, into RUN_DIR."""

    file: Annotated[tyro.conf.Positional[Path | None], tyro.conf.arg(metavar="[STUDY.toml]")] = None
    """the study definition; none: the default (or, for a RUN_DIR that holds a served run, its own)"""
    out: Path = Path("arteleop-served")
    """the run folder: a new or empty one begins the run; one that holds a served run carries on with its next participant"""
    host: str = "127.0.0.1"
    """interface to serve the page on; another than this machine's (0.0.0.0: every interface) lets other machines connect, each participant by their own link"""
    port: int = 8080
    """port to serve the page on; refused if it is taken (0: any free one)"""
    links: bool = False
    """each participant joins by a link of their own (printed as their session begins); always so when --host lets other machines connect"""
    public_url: str | None = None
    """the address participants open when a reverse proxy or a tunnel forwards to this server (https://study.example.org): links name it, with a wss:// socket for https; links are then always on"""
    width_px: int = 640
    """camera image width (px): the simulated cohort's; 320x240 keeps 30 frames/s on a loaded two-core machine"""
    height_px: int = 480
    """camera image height (px)"""


def study_serve(cmd: StudyServeCommand) -> int:
    from arteleop.ar_features import ViewConfig
    from arteleop.ar_features.host import check_host
    from arteleop.scene import HeadCameraConfig
    from arteleop.study import load_study_file
    from arteleop.study.serve import StudyServer
    from arteleop.study.session import served_run

    study = None if cmd.file is None else load_study_file(cmd.file)[0]
    camera = HeadCameraConfig(width_px=cmd.width_px, height_px=cmd.height_px)
    host = check_host(cmd.host, cmd.port)  # before the run folder is begun
    view = ViewConfig(host=cmd.host, port=cmd.port, public_url=cmd.public_url,
                      links=cmd.links or not host.loopback or cmd.public_url is not None)  # fmt: skip

    def tell_link(participant: str, url: str) -> None:
        print(f"participant {participant}'s link: {url}", flush=True)

    with (
        served_run(cmd.out, study) as run,
        StudyServer(run, view, camera, tell_link) as server,
    ):
        for notice in server.view.notices():
            print(notice, file=sys.stderr)
        person = run.current()
        if person is None:
            print(f"{cmd.out}: every session is done; nothing to serve.")
            return 0
        done = run.people.index(person)  # sessions end in plan order
        where = "by links" if server.view.gate else f"at {server.url}"
        print(f"serving {run.study.name!r} into {cmd.out} {where}: participant "
              f"{person.id} next, {done} of {len(run.people)} sessions done; Ctrl-C stops, "
              f"'arteleop study serve --out {cmd.out}' carries on")  # fmt: skip
        if server.observer_link is not None:
            print(f"the experimenter's view (read-only): {server.observer_link}", flush=True)
        try:
            finished = server.serve()
        except KeyboardInterrupt:
            finished = False
    if not finished:
        print(f"stopped; 'arteleop study serve --out {cmd.out}' carries on (a trial under way "
              "runs again)")  # fmt: skip
        return 130
    print(f"every session is done: arteleop analyze {cmd.out} --out {cmd.out / 'report'}")
    return 0


@dataclass(frozen=True)
class StudyAnswerCommand:
    """Merge real questionnaire answers into a run folder's questionnaire.csv."""

    run_dir: Annotated[tyro.conf.Positional[Path], tyro.conf.arg(metavar="RUN_DIR")]
    """the run folder"""
    answers: Annotated[tyro.conf.Positional[Path], tyro.conf.arg(metavar="ANSWERS.csv")]
    """CSV with participant, ar_class, item, score (docs/reference/data-format.md); these participants' answers replace the simulated ones"""


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
    """a mis-registered camera: its pose as the system uses it, moved by this (mm, camera frame), so the cloud sits off the ghost and the target (see 'arteleop trial --help')"""
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

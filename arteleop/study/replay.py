"""A trial played back from its run folder into the operator's view (``arteleop study replay``).

The trajectory file holds the arm's joints, the gripper's closure and the bowl's position at
100 Hz; at each camera tick the site is posed in that state (no physics), the head camera
renders it and the display frame carries the modality's layers, so the view shows what the
operator saw, give or take the bowl's tilt (the file keeps its position only).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from arteleop.ar_features import Display, modality_cues
from arteleop.errors import ConfigurationError, RunFolderError
from arteleop.robot import RIGHT_ARM_JOINTS
from arteleop.scene import HeadCameraConfig, RemoteSite, SiteConfig
from arteleop.study.plan import TrialSpec, plan_study
from arteleop.study.run_folder import STUDY_FILE, RunFolder
from arteleop.study.sites import StudySite
from arteleop.study.study_file import parse_study
from arteleop.teleop import LoopRates, display_frame
from arteleop.teleop.display_feed import with_cloud

REPLAY_COLUMNS: tuple[str, ...] = (
    "time_s", "gripper_target_x_m", "gripper_closure", *(f"{j}_rad" for j in RIGHT_ARM_JOINTS),
    "bowl_x_m", "bowl_y_m", "bowl_z_m",
)  # fmt: skip


@dataclass(frozen=True)
class ReplaySource:
    """What a replay needs of a run folder: the planned trial, its row and its trajectory."""

    spec: TrialSpec
    modality: str
    outcome: str
    trajectory: pd.DataFrame
    camera_registration: dict[str, Any] = field(default_factory=dict)
    """The study's :meth:`~arteleop.study.StudyConfig.camera_registration`."""
    depth_aids: bool = False
    """The study drew the depth aids (:attr:`~arteleop.study.StudyConfig.depth_aids`)."""


def load_replay(run_dir: Path, participant: str, trial_index: int) -> ReplaySource:
    """The trial ``participant``/``trial_index`` of the run in ``run_dir``."""
    folder = RunFolder(run_dir)
    if not folder.is_run_folder():
        raise RunFolderError(f"{folder.path} is not a run folder (no study.toml and manifest).")
    study = parse_study(
        (folder.path / STUDY_FILE).read_text(encoding="utf-8"), str(folder.path / STUDY_FILE)
    )
    rows = folder.done_rows()
    if (participant, trial_index) not in rows:
        have = sorted({p for p, _ in rows})
        raise RunFolderError(
            f"{folder.path / 'trials.csv'} has no trial {trial_index} of participant "
            f"{participant!r}. Participants with trials: {', '.join(have) or 'none'}."
        )
    row = folder.trials().set_index(["participant", "trial_index"]).loc[(participant, trial_index)]
    site = StudySite()
    try:
        plan = plan_study(study, site.practice_points(study.start_xy_m, study.target_xy_m))
    finally:
        site.close()
    spec = next(s for s in plan if s.key == (participant, trial_index))
    path = folder.path / str(row["trajectory_file"])
    if folder.path.resolve() not in path.resolve().parents:
        raise RunFolderError(
            f"{folder.path / 'trials.csv'}, {participant} trial {trial_index}, column "
            f"trajectory_file: '{row['trajectory_file']}' is outside the run folder; a "
            "trajectory file's path is inside it (trajectories/P01/1.csv)."
        )
    try:
        trajectory = pd.read_csv(path)
    except (OSError, UnicodeDecodeError, pd.errors.ParserError) as err:
        raise RunFolderError(f"{path}: cannot read the trajectory ({err}).") from err
    missing = [c for c in REPLAY_COLUMNS if c not in trajectory.columns]
    if missing:
        raise RunFolderError(
            f"{path} line 1: a replay needs the columns {', '.join(missing)}, which "
            "'arteleop study run' writes (docs/reference/data-format.md, trajectory files)."
        )
    if len(trajectory) == 0:
        raise RunFolderError(f"{path} has no rows to replay.")
    return ReplaySource(
        spec, str(row["modality"]), str(row["outcome"]), trajectory, study.camera_registration(),
        study.depth_aids,
    )  # fmt: skip


def replay_site(source: ReplaySource, camera: HeadCameraConfig | None = None) -> SiteConfig:
    """The site the trial ran on (its start and target, its camera's registration), with
    ``camera``'s image size and settings if given."""
    config = StudySite().site_config(source.spec, source.camera_registration)
    if camera is None:
        return config
    return replace(config, camera=replace(camera, **source.camera_registration))


def replay(
    source: ReplaySource,
    site: RemoteSite,
    display: Display,
    speed: float = 1.0,
    rates: LoopRates | None = None,
    on_frame: Callable[[float], None] | None = None,
) -> int:
    """Show the trial on ``display``, a frame per camera tick, posing ``site`` (built from
    :func:`replay_site`); returns the frames shown.

    Args:
        speed: Times real time; 0 plays as fast as it renders.
        on_frame: Called with each frame's time (s), e.g. for a progress bar.
    """
    if not (np.isfinite(speed) and speed >= 0):
        raise ConfigurationError(f"--speed {speed}: give 0 (as fast as it renders) or more.")
    rates = rates or LoopRates()
    t = source.trajectory
    times = t["time_s"].to_numpy()
    q = t[[f"{j}_rad" for j in RIGHT_ARM_JOINTS]].to_numpy()
    closure = t["gripper_closure"].to_numpy()
    bowl = t[["bowl_x_m", "bowl_y_m", "bowl_z_m"]].to_numpy()
    engaged = np.isfinite(t["gripper_target_x_m"].to_numpy()).tolist()
    cues = modality_cues(source.modality)
    frames = 0
    start = time.perf_counter()
    for frame_time in np.arange(0.0, times[-1] + 1e-9, 1.0 / rates.camera_hz):
        k = int(np.searchsorted(times, frame_time + 1e-9)) - 1
        site.pose(q[k], closure[k], bowl[k], times[k])
        state = site.observe()
        frame = display_frame(
            state, site.sight_bowl(), site.frames, site.config.workspace, cues, engaged[k],
            site.T_cloud_true, source.depth_aids, site.sight_marks(),
        )  # fmt: skip
        shown = with_cloud(frame, site.capture())
        if speed > 0:
            time.sleep(max(0.0, start + frame_time / speed - time.perf_counter()))
        display.show(shown)
        frames += 1
        if on_frame is not None:
            on_frame(float(frame_time))
    return frames

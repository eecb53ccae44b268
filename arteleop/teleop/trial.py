"""One pick-and-place trial as data: its configuration, its outcome and its result.

Completion time starts when the operator starts moving the arm after engaging and stops at the
first camera frame, after the release, in which the tracker finds the bowl at rest. Placement
error is the distance between that tracked position and the target.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import Enum

import numpy as np
from numpy.typing import NDArray

from arteleop.analysis import (
    AnalysisInputError,
    idle_share,
    log_dimensionless_jerk,
    normalized_jerk,
    path_length,
    spectral_arc_length,
    submovement_count,
)
from arteleop.ar_features import DisplayFrame, modality_cues
from arteleop.arrays import frozen_array
from arteleop.errors import ConfigurationError
from arteleop.scene import SiteConfig
from arteleop.teleop.clock import LoopRates
from arteleop.teleop.controller import ControllerConfig
from arteleop.teleop.network import NetworkConfig
from arteleop.teleop.timing import StageStats


@dataclass(frozen=True)
class TrialConfig:
    """A headless trial.

    Attributes:
        modality: AR modality shown to the operator.
        seed: Seed of every random source of the trial.
        timeout_s: Simulated time after which the trial ends as ``timeout``.
        rates: Control, physics and camera rates.
        network: Operator-to-robot link (the display's return link has the same delay).
        realtime: Pace the loop with the wall clock instead of running as fast as possible.
        render_camera: Render every camera frame (needed for the display and for wall-clock
            latency); otherwise frames are rendered only to track the bowl at the end. In real
            time, frames render in a process of their own, on another core, while the loop goes
            on; a camera tick that finds the previous frame still rendering is rendered as soon
            as that one is in, and a second such tick is skipped.
        site: The remote site.
        controller: Robot-side settings.
        record_trace: Record every control tick in ``TrialResult.trace`` (the study's
            trajectory files; about 4 MB of memory per simulated minute).
        skip_hidden_tracker_renders: After the release, do not render the tracker's frame when
            the tracker's model sees none of the bowl (:mod:`arteleop.teleop.task_monitor`);
            False renders every look, the plain path it is checked against.
        depth_aids: The display draws the depth aids (:attr:`DisplayFrame.depth_aids`).
        task: What the trial asks and how it is scored: a name :func:`~arteleop.teleop.trial_task`
            knows (``"pick-and-place"``, or ``"package.module:NAME"`` for a task of one's own).
    """

    modality: str = "full"
    seed: int = 0
    timeout_s: float = 120.0
    rates: LoopRates = field(default_factory=LoopRates)
    network: NetworkConfig = field(default_factory=NetworkConfig)
    realtime: bool = False
    render_camera: bool = False
    site: SiteConfig = field(default_factory=SiteConfig)
    controller: ControllerConfig = field(default_factory=ControllerConfig)
    record_trace: bool = False
    skip_hidden_tracker_renders: bool = True
    depth_aids: bool = False
    task: str = "pick-and-place"

    def __post_init__(self) -> None:
        # Imported here: a task's module brings the task monitor, which needs this one's Outcome.
        from arteleop.teleop.trial_task import trial_task

        modality_cues(self.modality)
        trial_task(self.task)
        if self.network.delay_s + 3 * self.network.jitter_s >= self.timeout_s:
            raise ConfigurationError(
                f"The network delay ({self.network.delay_s} s, jitter {self.network.jitter_s} s) "
                f"is longer than the trial timeout ({self.timeout_s} s): no command would ever "
                "arrive. Shorten the delay or lengthen TrialConfig.timeout_s."
            )


class Outcome(Enum):
    """How a trial ended."""

    SUCCESS = "success"
    """The bowl was released, came to rest and the camera's tracker found it."""
    TIMEOUT = "timeout"
    """``TrialConfig.timeout_s`` of simulated time passed before the release."""
    TRACKING_LOST = "tracking_lost"
    """The bowl was released, but the tracker had not found it at rest by the timeout."""
    DROPPED = "dropped"
    """The bowl fell off the table."""
    NOT_GRASPED = "not_grasped"
    """The operator stopped after closing the gripper without ever holding the bowl."""
    OPERATOR_STOPPED = "operator_stopped"
    """The operator source ran out (a recording ended) before the bowl was released."""


@dataclass(frozen=True)
class TrialProgress:
    """Where a running trial stands, at one camera tick.

    Attributes:
        time_s: Simulated time since the trial began (s).
        engaged: The arm follows the operator's hand.
        reachable: False while the IK target is out of reach (see ``loop.OUT_OF_REACH_M``):
            the arm has stopped at the nearest pose it can reach.
        motion_onset_s: When the completion timer started (s), or None before the reach.
        grasped: The bowl has been grasped.
        released: The bowl has been released after the grasp.
    """

    time_s: float
    engaged: bool
    reachable: bool
    motion_onset_s: float | None
    grasped: bool
    released: bool

    @property
    def elapsed_s(self) -> float:
        """The completion timer (s): 0 before the motion onset."""
        return 0.0 if self.motion_onset_s is None else self.time_s - self.motion_onset_s

    @property
    def state(self) -> str:
        """The trial's state in words, for a panel."""
        if not self.engaged:
            return "the robot is taking your hand: it follows your moves in a moment"
        if self.motion_onset_s is None:
            return "waiting for motion onset"
        if self.released:
            return "released: waiting for the bowl to be tracked"
        return "carrying the bowl" if self.grasped else "running"


@dataclass(frozen=True)
class TrialResult:
    """What happened in the trial.

    Latencies, one per camera frame, are the age of the newest operator sample the frame shows:
    ``latency_sim_ms`` in simulated time, at the frame's capture (network, control and camera
    rates); ``latency_wall_ms`` on the wall clock, once the frame is on the display (real-time
    runs that render the camera only, else empty).

    Attributes:
        modality: AR modality of the trial.
        seed: Seed of the trial.
        outcome: How it ended.
        completion_time_s: From motion onset to the tracked placement (s); NaN unless success.
        placement_error_m: Tracked bowl to target, in the table's plane (m); NaN unless success.
        placement_error_true_m: The same from ground truth (m); NaN unless released.
        grasped: Both pads held the bowl at some point.
        placed: The trial succeeded.
        grasp_attempts: Closures of the gripper.
        duration_s: Simulated time at the end (s).
        motion_onset_s: When the reach started, the completion timer's start (s); NaN if never.
        hand_time_s: (N,) times of the reconstructed hand while engaged (s).
        hand_m: (N, 3) the reconstructed hand, torso frame (m).
        latency_sim_ms: (frames,) see above.
        latency_wall_ms: (frames,) see above.
        colocation_px: (camera ticks,) how far the ghost's gripper lands from the real gripper
            in the camera's image, the view placed with the camera's registration (px): 0 for
            a perfect one (``HeadCameraConfig.registration_offset_*``).
        colocation_m: (camera ticks,) the same in space, in the camera's frame (m).
        stages: Service time and latency per stage of the loop.
        counts: Samples sent, lost and late; samples the wearable lost; unreachable IK ticks;
            held samples; camera frames skipped; tracker renders skipped.
        trace: With ``TrialConfig.record_trace``, every control tick by the columns of
            :data:`~arteleop.teleop.trace.TRACE_COLUMNS`; else None.
        final_frame: The display frame the trial ended on, as it reaches the operator a return
            trip later: what a person sees of the outcome (the frame's content, without its
            point cloud); None before the first camera frame.
    """

    modality: str
    seed: int
    outcome: Outcome
    completion_time_s: float
    placement_error_m: float
    placement_error_true_m: float
    grasped: bool
    placed: bool
    grasp_attempts: int
    duration_s: float
    motion_onset_s: float
    hand_time_s: NDArray[np.float64]
    hand_m: NDArray[np.float64]
    latency_sim_ms: NDArray[np.float64]
    latency_wall_ms: NDArray[np.float64]
    colocation_px: NDArray[np.float64]
    colocation_m: NDArray[np.float64]
    stages: list[StageStats]
    counts: dict[str, int]
    trace: dict[str, NDArray[np.float64]] | None = None
    final_frame: DisplayFrame | None = None

    def __post_init__(self) -> None:
        for name in (
            "hand_time_s", "hand_m", "latency_sim_ms", "latency_wall_ms", "colocation_px",
            "colocation_m",
        ):  # fmt: skip
            object.__setattr__(self, name, frozen_array(getattr(self, name)))
        if self.trace is not None:
            object.__setattr__(self, "trace", {k: frozen_array(v) for k, v in self.trace.items()})

    def movement(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """(time_s, hand_m) of the hand from motion onset to the end: the timed movement."""
        keep = self.hand_time_s >= self.motion_onset_s  # none when the onset is NaN
        return self.hand_time_s[keep], self.hand_m[keep]

    def to_row(self) -> dict[str, object]:
        """The columns of ``trials.csv`` (docs/reference/data-format.md) that a trial knows.

        Smoothness and path length are those of the timed movement (motion onset to the end),
        through the analysis's filter; empty (NaN) when the hand barely moved.
        """
        t, hand = self.movement()
        try:
            jerk, length = normalized_jerk(t, hand, "xy"), path_length(t, hand)
            ldlj, sparc = log_dimensionless_jerk(t, hand, "xy"), spectral_arc_length(t, hand, "xy")
            peaks = float(submovement_count(t, hand, "xy"))
            idle = idle_share(t, hand, "xy")
        except AnalysisInputError:  # fewer than 8 samples, or no movement
            jerk = length = ldlj = sparc = peaks = idle = float("nan")
        latency = self.latency_wall_ms if len(self.latency_wall_ms) else self.latency_sim_ms
        return {
            "modality": self.modality,
            "seed": self.seed,
            "outcome": self.outcome.value,
            "completion_time_s": self.completion_time_s,
            "placement_error_m": self.placement_error_m,
            "placement_error_true_m": self.placement_error_true_m,
            "normalized_jerk_xy": jerk,
            "ldlj_xy": ldlj,
            "sparc_xy": sparc,
            "submovements_xy": peaks,
            "idle_share_xy": idle,
            "grasp_attempts": self.grasp_attempts,
            "hand_path_length_m": length,
            "latency_median_ms": _median(latency),
            "colocation_error_px": _median(self.colocation_px),
            "colocation_error_m": _median(self.colocation_m),
        }


def _median(values: NDArray[np.float64]) -> float:
    return float(np.median(values)) if len(values) else float("nan")

"""One pick-and-place trial, headless: operator -> network -> robot -> physics -> camera.

Completion time (STUDY.md §1) starts when the operator starts moving the arm after engaging and
stops at the first camera frame, after the release, in which the tracker finds the bowl at rest.
Placement error is the distance between that tracked position and the target.
"""

from __future__ import annotations

import time
from collections import deque
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np
from numpy.typing import ArrayLike, NDArray

from arteleop.ar_features import modality_cues
from arteleop.errors import ConfigurationError
from arteleop.operator.perception import DisplayView
from arteleop.robot import GRIPPER_FRAME
from arteleop.scene import (
    BowlTracker,
    RemoteSite,
    RGBDFrame,
    SiteConfig,
    frame_to_point_cloud,
)
from arteleop.teleop.clock import LoopClock, LoopRates
from arteleop.teleop.controller import ControllerConfig, ControllerState, TeleopController
from arteleop.teleop.network import NetworkConfig, NetworkLink
from arteleop.teleop.sources import OperatorSource, WearableSample
from arteleop.teleop.timing import StageStats, StageTimer

START_SPEED_M_S = 0.05
"""Hand speed that marks the start of the reach (m/s)."""
TRACKING_PERIOD_S = 0.5
"""After the release, the bowl tracker runs on every fifteenth camera frame (2 Hz)."""
BOWL_AT_REST_M_S = 0.01


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

    def __post_init__(self) -> None:
        modality_cues(self.modality)
        if self.network.delay_s + 3 * self.network.jitter_s >= self.timeout_s:
            raise ConfigurationError(
                f"The network delay ({self.network.delay_s} s, jitter {self.network.jitter_s} s) "
                f"is longer than the trial timeout ({self.timeout_s} s): no command would ever "
                "arrive. Shorten the delay or lengthen TrialConfig.timeout_s."
            )


@dataclass
class TrialResult:
    """What happened in the trial.

    Latencies, one per camera frame, are the age of the newest operator sample the frame shows:
    ``latency_sim_ms`` in simulated time, at the frame's capture (network, control and camera
    rates); ``latency_wall_ms`` on the wall clock, once the frame's point cloud is on the display
    (real-time runs that render the camera only, else empty).
    """

    outcome: str
    completion_time_s: float
    placement_error_m: float
    placement_error_true_m: float
    grasped: bool
    placed: bool
    grasp_attempts: int
    duration_s: float
    hand_time_s: NDArray[np.float64]
    hand_m: NDArray[np.float64]
    latency_sim_ms: NDArray[np.float64]
    latency_wall_ms: NDArray[np.float64]
    stages: list[StageStats]
    counts: dict[str, int]


class CloudDisplay(Protocol):
    """Where the camera's point cloud is shown, e.g. :class:`arteleop.ar_features.OperatorView`."""

    def show_cloud(self, points_m: ArrayLike, colors: ArrayLike) -> None: ...


def run_trial(
    source: OperatorSource,
    config: TrialConfig,
    site: RemoteSite | None = None,
    display: CloudDisplay | None = None,
) -> TrialResult:
    """Run one trial to its end; builds the site from ``config.site`` unless one is given.

    With a ``display``, every camera frame's point cloud is shown on it (this needs
    ``config.render_camera``).
    """
    if display is not None and not config.render_camera:
        raise ConfigurationError(
            "A display needs camera frames: run the trial with TrialConfig(render_camera=True)."
        )
    own_site = site is None
    site = site or RemoteSite(config.site)
    try:
        return _Trial(source, config, site, display).run()
    finally:
        if own_site:
            site.close()


class _Trial:
    def __init__(
        self,
        source: OperatorSource,
        config: TrialConfig,
        site: RemoteSite,
        display: CloudDisplay | None,
    ) -> None:
        self.source, self.config, self.site, self.display = source, config, site, display
        rng = np.random.default_rng(config.seed)
        self.link: NetworkLink[WearableSample] = NetworkLink(config.network, rng)
        if config.realtime and config.render_camera:
            site.start_render_process()  # before the clock starts: it takes a few seconds
        self.clock = LoopClock(config.rates, config.realtime)
        self.timer = StageTimer()
        self.control = TeleopController(
            site,
            source.arm,
            source.calibration,
            1.0 / config.rates.control_hz,
            config.controller,
            self.timer,
        )
        self.cues = modality_cues(config.modality)
        self.tracker = BowlTracker(site.config.workspace.bowl)
        self.views: deque[DisplayView] = deque(maxlen=64)
        self.hand_t: list[float] = []
        self.hand_p: list[NDArray[np.float64]] = []
        self.latency: list[float] = []
        self.latency_wall: list[float] = []
        self._sample_wall: deque[tuple[float, float]] = deque()  # (sample time, wall clock)
        self._async_camera = config.realtime and config.render_camera
        self._requested = (0.0, -np.inf)  # (wall clock, newest applied sample) of the request
        self._frame_owed = False
        self.frames_skipped = 0
        self.t_start: float | None = None
        self.grasped = False
        self.grasp_attempts = 0
        self.released = False
        self.dropped_samples = 0
        self._was_closed = False
        self._next_track_s = 0.0

    def run(self) -> TrialResult:
        site, cfg = self.site, self.config
        ws = site.config.workspace
        target = ws.target_m
        while True:
            tick = self.clock.next()
            t = tick.time_s
            if self._async_camera:
                self._collect_frame()
            if t > cfg.timeout_s:
                return self._result("timeout", t)
            if tick.camera:
                self._camera(t)
                if self.released and t >= self._next_track_s and self._bowl_at_rest():
                    self._next_track_s = t + TRACKING_PERIOD_S
                    frame = site.capture()
                    track = self.tracker.track(frame, ws.table_top_z_m)
                    if track.found and track.position_m is not None:
                        err = float(np.linalg.norm(track.position_m[:2] - target[:2]))
                        return self._result("success", t, err)
                if site.bowl_position_m()[2] < ws.table_top_z_m - 0.05:
                    return self._result("dropped", t)
            if tick.control:
                if not self._control(t):
                    return self._result("operator_stopped", t)
            if tick.physics:
                w0 = time.perf_counter()
                self.control.physics_tick()
                self.timer.record("trajectory", w0)
                w0 = time.perf_counter()
                site.step()
                self.timer.record("physics", w0)

    def _control(self, t: float) -> bool:
        view = self._view(t)
        w0 = time.perf_counter()
        sample = self.source.sample(t, view)
        self.timer.record("operator_input", w0)
        if sample is None:
            return False
        if self.config.realtime:
            self._sample_wall.append((sample.time_s, w0))
        self.link.send(sample.time_s, sample, t)
        w0 = time.perf_counter()
        for _, received in self.link.receive(t):
            if received.sensor_quat_wxyz is None:
                self.dropped_samples += 1
            self.control.receive(received.time_s, received.sensor_quat_wxyz, received.grip)
        self.timer.record("reconstruction", w0)
        w0 = time.perf_counter()
        self.control.control_tick()
        self.timer.record("control_tick", w0)
        hand = self.control.last_hand
        if self.control.state is ControllerState.ENGAGED and hand is not None:
            self.hand_t.append(hand.time_s)
            self.hand_p.append(hand.hand_m)
            if self.t_start is None and self.control.hand_speed_m_s > START_SPEED_M_S:
                self.t_start = t
        self._grasp_state()
        return True

    def _grasp_state(self) -> None:
        closed = self.control.grip.closed
        if closed and not self._was_closed:
            self.grasp_attempts += 1
        if closed and all(self.site.robot.gripper.touching(self.site.bowl_id)):
            self.grasped = True
        if self.grasped and not closed:
            self.released = True
        self._was_closed = closed

    def _bowl_at_rest(self) -> bool:
        return self.site.bowl_speed_m_s() < BOWL_AT_REST_M_S

    def _camera(self, t: float) -> None:
        """A camera tick: the display's content now (rendered if asked), and its latency."""
        site = self.site
        applied = self.control.applied_sample_time_s
        if self._async_camera:
            if not site.frame_pending:
                self._request_frame()
            elif self._frame_owed:
                self.frames_skipped += 1  # two ticks while one frame renders: drop one
            else:
                self._frame_owed = True  # render it as soon as the current frame is in
        elif self.config.render_camera:
            w0 = time.perf_counter()
            frame = site.capture()
            self.timer.record("camera", w0)
            self._show(frame, applied)
        if np.isfinite(self.control.applied_sample_time_s):
            self.latency.append(t - self.control.applied_sample_time_s)
        gripper = site.robot.link_transform(GRIPPER_FRAME)[:3, 3]
        in_view = site.camera.sees(gripper)
        self.views.append(DisplayView(
            t, site.camera.T_base_camera[:3, 3].copy(), gripper, in_view,
            site.robot.gripper.closure(),
            site.bowl_position_m(), site.config.workspace.target_m, self.cues,
            self.control.state is ControllerState.ENGAGED,
        ))  # fmt: skip

    def _request_frame(self) -> None:
        self.site.request_frame()
        self._requested = (time.perf_counter(), self.control.applied_sample_time_s)
        self._frame_owed = False

    def _collect_frame(self) -> None:
        """Real time: pick up the frame the render process has finished, if any."""
        frame = self.site.poll_frame()
        if frame is not None:
            requested_wall, applied = self._requested
            self.timer.record("camera", requested_wall)
            if self._frame_owed:
                self._request_frame()  # a tick came while this one rendered
            self._show(frame, applied)

    def _show(self, frame: RGBDFrame, applied: float) -> None:
        """Point cloud and display update of a frame that shows samples up to ``applied``."""
        w0 = time.perf_counter()
        cloud = frame_to_point_cloud(frame, stride=2)
        self.timer.record("point_cloud", w0)
        if self.display is not None:
            w0 = time.perf_counter()
            self.display.show_cloud(cloud.points_m, cloud.colors)
            self.timer.record("display", w0)
        self._wall_latency(applied)

    def _wall_latency(self, applied: float) -> None:
        """Real time only: wall-clock age of the newest sample a frame shows (``applied``) once
        the frame has been shown (or turned into a point cloud, without a display)."""
        samples = self._sample_wall
        while len(samples) > 1 and samples[1][0] <= applied:
            samples.popleft()
        if samples and samples[0][0] == applied:
            self.latency_wall.append(time.perf_counter() - samples[0][1])

    def _view(self, t: float) -> DisplayView:
        """The newest display content that has reached the operator (return-link delay)."""
        delay = self.config.network.delay_s
        for view in reversed(self.views):
            if view.time_s <= t - delay:
                return view
        if self.views:
            return self.views[0]
        self._camera(t)
        return self.views[-1]

    def _result(self, outcome: str, t: float, error_m: float = float("nan")) -> TrialResult:
        ws = self.site.config.workspace
        true_err = float(np.linalg.norm(self.site.bowl_position_m()[:2] - ws.target_m[:2]))
        start = self.t_start if self.t_start is not None else t
        counts = {
            "samples_sent": self.link.sent, "samples_lost_network": self.link.lost,
            "samples_late": self.link.late, "samples_lost_wearable": self.dropped_samples,
            "unreachable_ticks": self.control.unreachable_ticks,
            "held_samples": self.control.reconstructor.held if self.control.reconstructor else 0,
            "camera_frames_skipped": self.frames_skipped,
        }  # fmt: skip
        return TrialResult(
            outcome=outcome,
            completion_time_s=t - start if outcome == "success" else float("nan"),
            placement_error_m=error_m,
            placement_error_true_m=true_err if self.released else float("nan"),
            grasped=self.grasped,
            placed=outcome == "success",
            grasp_attempts=self.grasp_attempts,
            duration_s=t,
            hand_time_s=np.array(self.hand_t),
            hand_m=np.array(self.hand_p).reshape(-1, 3),
            latency_sim_ms=np.array(self.latency) * 1000,
            latency_wall_ms=np.array(self.latency_wall) * 1000,
            stages=self.timer.summary(),
            counts=counts,
        )

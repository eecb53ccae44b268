"""The teleoperation loop of one trial: operator -> network -> robot -> physics -> camera.

One clock fires the stages at their own rates; each stage hands plain data to the next. An
operator sample goes: ``OperatorSource.sample`` -> ``NetworkLink`` -> ``TeleopController.receive``
(reconstruction) -> ``TeleopController.control_tick`` (mapping, IK, trajectory target; returns
the gripper's :class:`ArmCommand`) -> ``TeleopController.physics_tick`` (the arm's joint targets)
-> ``RemoteSite.apply`` -> ``RemoteSite.step``. The site is read only through
``RemoteSite.observe``; the display and the operator see :class:`DisplayFrame` s.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from arteleop.ar_features import Display, DisplayFrame, modality_cues
from arteleop.errors import ConfigurationError
from arteleop.operator import OperatorSource, SyntheticSource, WearableSample, task_source
from arteleop.robot import RIGHT_ARM_JOINTS
from arteleop.scene import RemoteSite, SiteState
from arteleop.teleop.clock import LoopClock
from arteleop.teleop.controller import TeleopController
from arteleop.teleop.display_feed import DisplayFeed
from arteleop.teleop.latency import LatencyAccount
from arteleop.teleop.network import NetworkLink
from arteleop.teleop.predictor import CommandPredictor
from arteleop.teleop.timing import StageTimer
from arteleop.teleop.trace import TrialTrace
from arteleop.teleop.trial import Outcome, TrialConfig, TrialProgress, TrialResult
from arteleop.teleop.trial_task import TaskSite, trial_task

OUT_OF_REACH_S = 0.5
OUT_OF_REACH_M = 0.01
"""The target is reported out of reach while the gripper is more than ``OUT_OF_REACH_M`` (m)
from it in the table's plane and the IK has flagged it unreachable within the last
``OUT_OF_REACH_S`` (s): with the operator's tremor and the IMUs' noise, the IK's flag flickers at
the edge of the reach. A target under the table's top, where the IK holds the gripper just above
it, is not out of reach: the gripper is seen on the table (in the pointing task, aimed a few
centimetres into it, the notice was on for most of a trial)."""


def run_trial(
    source: OperatorSource,
    config: TrialConfig,
    site: RemoteSite | None = None,
    display: Display | None = None,
    progress: Callable[[TrialProgress], None] | None = None,
) -> TrialResult:
    """Run one trial to its end; builds the site from ``config.site`` unless one is given.

    With a ``display``, every camera frame is shown on it (this needs ``config.render_camera``).
    ``progress`` is called with the trial's :class:`TrialProgress` at every camera tick; an
    exception it raises ends the trial and reaches the caller (a stop button, Ctrl-C).
    """
    if display is not None and not config.render_camera:
        raise ConfigurationError(
            "A display needs camera frames: run the trial with TrialConfig(render_camera=True)."
        )
    own_site = site is None
    site = site or RemoteSite(config.site)
    try:
        return _Loop(source, config, site, display, progress).run()
    finally:
        if own_site:
            site.close()


def trial_operator(site: RemoteSite, config: TrialConfig, **kwargs: Any) -> SyntheticSource:
    """The synthetic operator of a trial on ``site``, doing the trial's task
    (:attr:`TrialConfig.task`), seeded from the trial's seed; it aligns its hand on the gripper
    where it rests now. ``kwargs`` go to :func:`~arteleop.operator.task_source` (``params``,
    ``traits``, ``wearable``)."""
    told = TaskSite(site.config.workspace, site.observe().gripper_m, site.gripper_gap_range_m)
    task = trial_task(config.task).operator_task(told)
    return task_source(task, config.controller.mapping, config.seed, **kwargs)


def display_frame_at(
    source: OperatorSource, config: TrialConfig, time_s: float, site: RemoteSite | None = None
) -> DisplayFrame:
    """The display frame, point cloud included, that a trial captures at ``time_s`` (s), as it
    reaches the display (a return trip later, with the predicted arm): the trial runs to then,
    rendering every camera frame; for pictures and tests of the view."""
    return display_frames_at(source, config, (time_s,), site)[0]


def display_frames_at(
    source: OperatorSource,
    config: TrialConfig,
    times_s: Sequence[float],
    site: RemoteSite | None = None,
) -> tuple[DisplayFrame, ...]:
    """The display frames one trial captures at each of ``times_s`` (s), in one run (see
    :func:`display_frame_at`)."""
    end_s = max(times_s) + config.network.delay_s + 1.0 / config.rates.camera_hz
    config = replace(config, timeout_s=end_s, render_camera=True)
    captured = _FramesAt(times_s)
    run_trial(source, config, site, captured)
    frames = []
    for time_s, frame in zip(times_s, captured.frames, strict=True):
        if frame is None:
            raise ConfigurationError(
                f"The trial ended before {time_s} s, so it shows nothing then: choose an "
                "earlier time."
            )
        frames.append(frame)
    return tuple(frames)


class _FramesAt:
    """Keeps the first frame shown at or after each of ``times_s`` (s)."""

    def __init__(self, times_s: Sequence[float]) -> None:
        self._times_s = times_s
        self.frames: list[DisplayFrame | None] = [None] * len(times_s)

    def show(self, frame: DisplayFrame) -> None:
        for k, time_s in enumerate(self._times_s):
            if self.frames[k] is None and frame.time_s >= time_s - 1e-9:
                self.frames[k] = frame


class _Loop:
    def __init__(
        self,
        source: OperatorSource,
        config: TrialConfig,
        site: RemoteSite,
        display: Display | None,
        progress: Callable[[TrialProgress], None] | None = None,
    ) -> None:
        self.source, self.config, self.site = source, config, site
        self._progress = progress
        ws = site.config.workspace
        self.link: NetworkLink[WearableSample] = NetworkLink(
            config.network, np.random.default_rng(config.seed)
        )
        background = config.realtime and config.render_camera
        if background:
            site.start_render_process()  # before the clock starts: it takes a few seconds
        # A batch loop that renders nothing has nothing to do between its stages' ticks.
        delivering = config.render_camera
        self.clock = LoopClock(
            config.rates, config.realtime, idle_ticks=delivering, stop_s=config.timeout_s
        )
        self.timer = StageTimer()
        cues = modality_cues(config.modality)

        def controller(timer: StageTimer) -> TeleopController:
            return TeleopController(
                site.description.urdf_path,
                site.kinematics.limits(RIGHT_ARM_JOINTS),
                site.observe(links=()).arm_q_rad,
                source,
                config.rates,
                ws.table_box(),
                config.controller,
                timer,
            )

        self.control = controller(self.timer)
        # The predictive ghost's model runs where it is shown: in the trial's cues, or in a
        # view whose panel can switch it on.
        self.predictor = (
            CommandPredictor(controller(StageTimer()))
            if cues.predictive_ghost or display is not None
            else None
        )
        self.monitor = trial_task(config.task).monitor(ws)
        self.latency = LatencyAccount()
        self.feed = DisplayFeed(
            site,
            cues,
            render=config.render_camera,
            in_background=background,
            return_delay_s=config.network.delay_s,
            display=display,
            timer=self.timer,
            latency=self.latency,
            track_every=config.rates.frames_per_track,
            depth_aids=config.depth_aids,
        )
        self._background = background
        self._delivering = delivering
        self._gate_tracker = config.skip_hidden_tracker_renders
        self.hand_t: list[float] = []
        self.hand_p: list[NDArray[np.float64]] = []
        self.samples_lost_wearable = 0
        self.trace = TrialTrace() if config.record_trace else None
        self._received: WearableSample | None = None
        self._unreachable_s = -np.inf  # when the IK last flagged its target out of reach
        # The out-of-reach notice is off, as the last camera tick found it: batch and real-time
        # runs sample the IK's flag alike.
        self._notice_off = True

    def run(self) -> TrialResult:
        site, control, timer = self.site, self.control, self.timer
        while True:
            tick = self.clock.next()
            t = tick.time_s
            if self._background:
                self.feed.poll(control.engaged, self._notice_off, control.applied_sample_time_s)
            if self._delivering:
                self.feed.deliver(t)
            if t > self.config.timeout_s:
                return self._result(self.monitor.timed_out(), t)
            if tick.camera or tick.control:
                # One observation for both: nothing moves the physics between their turns.
                state = site.observe()
                if tick.camera:
                    self._notice_off = self._reachable(t)
                    self.feed.camera_tick(
                        state, control.engaged, self._notice_off, control.applied_sample_time_s
                    )
                    outcome = self.monitor.camera(
                        t, state, site.capture, site.sight_bowl if self._gate_tracker else None
                    )
                    if outcome is not None:
                        return self._result(outcome, t)
                    if self._progress is not None:
                        self._progress(self._status(t))
                if tick.control and not self._control(t, state):
                    return self._result(self.monitor.operator_stopped(), t)
            if tick.physics:
                with timer.stage("trajectory"):
                    command = control.physics_tick()
                    if command is not None:
                        site.apply(command)
                with timer.stage("physics"):
                    site.step()

    def _control(self, t: float, state: SiteState) -> bool:
        """One control tick; False once the operator has stopped before letting go of the bowl.

        An operator who stops after the release (a recording that ends there) has done the task:
        the robot holds while the bowl settles and is tracked. ``state``: the site now.
        """
        control, timer = self.control, self.timer
        frame = self._as_seen(self.feed.seen_by_operator(t))
        predictor = self.predictor
        created_wall = time.perf_counter()
        with timer.stage("operator_input"):
            sample = self.source.sample(t, frame)
        if sample is None and not self.monitor.released:
            return False
        if sample is not None:
            if self.config.realtime:
                self.latency.sample_created(sample.time_s, created_wall)
            self.link.send(sample.time_s, sample, t)
            if predictor is not None:
                predictor.sent(sample)
        if predictor is not None:
            self.feed.predicted = predictor.tick(t, frame)
        with timer.stage("reconstruction"):
            for _, received in self.link.receive(t):
                if received.sensor_quat_wxyz is None:
                    self.samples_lost_wearable += 1
                control.receive(received.time_s, received.sensor_quat_wxyz, received.grip)
                self._received = received
        with timer.stage("control_tick"):
            command = control.control_tick(state)
            if command is not None:
                self.site.apply(command)
        hand = control.last_hand
        moving = None
        if control.engaged and hand is not None:
            # A tick without a new sample (one came late, two come at the next) adds nothing.
            if not self.hand_t or hand.time_s > self.hand_t[-1]:
                self.hand_t.append(hand.time_s)
                self.hand_p.append(hand.hand_m)
            moving = control.hand_speed_m_s
        self.monitor.control(t, moving, control.grip.closed, state)
        if self.trace is not None:
            got = self._received
            self.trace.add(
                t, None if hand is None else hand.hand_m, np.nan if got is None else got.grip,
                None if got is None else got.sensor_quat_wxyz, control.last_target_m,
                state.gripper_m, state.gripper_closure, state.arm_q_rad, state.bowl_m,
            )  # fmt: skip
        return True

    def _as_seen(self, frame: DisplayFrame) -> DisplayFrame:
        """``frame`` as the operator sees it: with the newest prediction of the arm, if any."""
        predictor = self.predictor
        if predictor is not None and predictor.predicted is not None:
            return replace(frame, predicted=predictor.predicted)
        return frame

    def _reachable(self, t: float) -> bool:
        """The out-of-reach notice is off at the camera tick ``t`` (s): see
        :data:`OUT_OF_REACH_M`; the IK's flag is sampled at the camera's ticks."""
        control = self.control
        ik, target = control.last_ik, control.last_target_m
        if ik is None or target is None:
            return True
        if not ik.reachable:
            self._unreachable_s = t
        gap = target[:2] - control.ik.gripper_transform()[:2, 3]
        short = float(np.hypot(*gap)) > OUT_OF_REACH_M
        return not (short and t - self._unreachable_s <= OUT_OF_REACH_S)

    def _status(self, t: float) -> TrialProgress:
        control, monitor = self.control, self.monitor
        return TrialProgress(
            time_s=t,
            engaged=control.engaged,
            reachable=self._notice_off,
            motion_onset_s=monitor.motion_onset_s,
            grasped=monitor.grasped,
            released=monitor.released,
        )

    def _result(self, outcome: Outcome, t: float) -> TrialResult:
        monitor, target = self.monitor, self.site.config.workspace.target_m
        bowl = self.site.observe(links=()).bowl_m
        true_err = float(np.linalg.norm(bowl[:2] - target[:2]))
        onset = monitor.motion_onset_s
        counts = {
            "samples_sent": self.link.sent, "samples_lost_network": self.link.lost,
            "samples_late": self.link.late, "samples_lost_wearable": self.samples_lost_wearable,
            "unreachable_ticks": self.control.unreachable_ticks,
            "held_samples": r.held if (r := self.control.reconstructor) else 0,
            "camera_frames_skipped": self.feed.frames_skipped,
            "tracker_renders_skipped": self.monitor.renders_skipped,
        }  # fmt: skip
        success = outcome is Outcome.SUCCESS
        return TrialResult(
            modality=self.config.modality,
            seed=self.config.seed,
            outcome=outcome,
            completion_time_s=t - (onset if onset is not None else t) if success else np.nan,
            placement_error_m=monitor.placement_error_m if success else np.nan,
            placement_error_true_m=true_err if monitor.released else np.nan,
            grasped=monitor.grasped,
            placed=success,
            grasp_attempts=monitor.grasp_attempts,
            duration_s=t,
            motion_onset_s=onset if onset is not None else np.nan,
            hand_time_s=np.array(self.hand_t),
            hand_m=np.array(self.hand_p).reshape(-1, 3),
            latency_sim_ms=self.latency.sim_ms,
            latency_wall_ms=self.latency.wall_ms,
            colocation_px=np.array(self.feed.colocation_px),
            colocation_m=np.array(self.feed.colocation_m),
            stages=self.timer.summary(),
            counts=counts,
            trace=None if self.trace is None else self.trace.columns(),
            final_frame=None if (last := self.feed.last_frame) is None else self._as_seen(last),
        )

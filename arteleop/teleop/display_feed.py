"""The display side of the loop: one :class:`DisplayFrame` per camera tick.

At each camera tick the feed builds the frame of what the remote system knows at that instant
(the arm's encoders, the gripper, the bowl as the camera tracks it, the target, the cues, the
engaged indicator). The bowl's track comes from the model of the tracker
(:meth:`RemoteSite.sight_bowl`; the tracker itself costs 60-90 ms a frame, more than a camera
period), updated at the tracker's rate and held in between. When
the camera renders, the frame carries the point cloud and goes to the display: in place in
batch runs; in real time, through the render process on the other core, shown when it comes
back. The operator sees each frame once the return link's delay has passed, on the display as
in the synthetic operator's eyes; a frame reaches the display with the newest prediction of the
arm (:class:`~arteleop.teleop.predictor.CommandPredictor`) for the predictive ghost.
"""

from __future__ import annotations

import time
from collections import deque
from dataclasses import replace

import numpy as np
from numpy.typing import NDArray

from arteleop.ar_features import ArCues, Display, DisplayFrame, PredictedArm, ViewAssets
from arteleop.errors import SimulationError
from arteleop.robot import (
    GRIPPER_FRAME,
    HEAD_PAN_JOINT,
    LEFT_ARM_JOINTS,
    LEFT_FINGER_JOINTS,
    RIGHT_ARM_JOINTS,
    RIGHT_FINGER_JOINTS,
)
from arteleop.scene import (
    BASE_FRAME,
    START_MARKER_FRAME,
    TARGET_MARKER_FRAME,
    BowlTrack,
    MarksSight,
    RemoteSite,
    RGBDFrame,
    SiteFrames,
    SiteState,
    Workspace,
    bowl_mesh,
    frame_to_point_cloud,
)
from arteleop.teleop.latency import LatencyAccount
from arteleop.teleop.timing import StageTimer

CLOUD_STRIDE = 2
"""The display's cloud keeps every second row and column of the depth image."""


def with_cloud(frame: DisplayFrame, rgbd: RGBDFrame, stride: int = CLOUD_STRIDE) -> DisplayFrame:
    """``frame`` with the point cloud of ``rgbd`` for the view: decimated by ``stride`` (1 for
    a frame rendered already thinned by :data:`CLOUD_STRIDE`) and placed with the frame's
    camera pose (the graph's, as the layers are)."""
    cloud = frame_to_point_cloud(rgbd, stride, frame.T_base_camera)
    return replace(
        frame,
        cloud_points_m=cloud.points_m,
        cloud_colors=cloud.colors,
        cloud_spacing_rad=cloud.spacing_rad,
    )


def display_frame(
    state: SiteState,
    bowl: BowlTrack,
    frames: SiteFrames,
    workspace: Workspace,
    cues: ArCues,
    engaged: bool,
    T_cloud_true: NDArray[np.float64] | None = None,
    depth_aids: bool = False,
    marks: MarksSight | None = None,
    reachable: bool = True,
) -> DisplayFrame:
    """The display's content for a site state and the bowl's track at that instant, without a
    cloud. Placed through the site's frames: the eye at the camera's registration, the ghost at
    the arm's encoder readings, the target mesh at the target marker; ``T_cloud_true``: the
    registration's error (:attr:`RemoteSite.T_cloud_true`); ``depth_aids``: drawn
    (:attr:`DisplayFrame.depth_aids`); ``marks``: how much of the marks the cloud draws
    (:meth:`RemoteSite.sight_marks`; None: all of them); ``reachable``: the out-of-reach notice
    is off (:attr:`DisplayFrame.reachable`)."""
    marks = marks or MarksSight()
    frames.set_joints(dict(zip(RIGHT_ARM_JOINTS, state.arm_q_rad.tolist(), strict=True)))
    grasp = workspace.bowl.grasp_offset_m()
    return DisplayFrame(
        time_s=state.time_s,
        T_base_camera=frames.T_base_camera,
        arm_q_rad=state.arm_q_rad,
        T_base_gripper=frames.T(BASE_FRAME, GRIPPER_FRAME),
        gripper_closure=state.gripper_closure,
        gripper_in_camera=state.camera.sees(state.gripper_m),
        bowl_m=bowl.position_m if bowl.found else None,
        grasp_radius_m=float(np.hypot(grasp[0], grasp[1])),
        grasp_height_m=float(grasp[2]),
        target_m=frames.T(BASE_FRAME, TARGET_MARKER_FRAME)[:3, 3],
        start_m=frames.T(BASE_FRAME, START_MARKER_FRAME)[:3, 3],
        target_radius_m=workspace.target_circle_radius_m,
        cues=cues,
        engaged=engaged,
        T_cloud_true=T_cloud_true,
        depth_aids=depth_aids,
        target_drawn=marks.target_share,
        start_drawn=marks.start_share,
        reachable=reachable,
    )


RENDER_TIMEOUT_S = 30.0
"""The longest wait for the render process's frame (s): its start takes a few seconds."""


def site_frame(
    site: RemoteSite, cues: ArCues, in_background: bool = False, depth_aids: bool = False
) -> DisplayFrame:
    """The display of ``site`` as it is now, its cloud rendered: what a view shows between
    trials (the arm at rest, the bowl where the next trial starts), before any operator.
    ``in_background``: rendered by the site's render process, as a real-time trial's frames
    are (a thread other than the site's own cannot use its OpenGL context); ``depth_aids``:
    drawn."""
    frame = display_frame(
        site.observe(), site.sight_bowl(), site.frames, site.config.workspace, cues, False,
        site.T_cloud_true, depth_aids, site.sight_marks(),
    )  # fmt: skip
    if not in_background:
        return with_cloud(frame, site.capture())
    end = time.monotonic() + RENDER_TIMEOUT_S
    while site.frame_pending:  # a stopped trial's frame still rendering: not this one
        site.poll_frame()
        _wait_for_render(end)
    site.request_frame(CLOUD_STRIDE)
    while (rgbd := site.poll_frame()) is None:
        _wait_for_render(end)
    return with_cloud(frame, rgbd, stride=1)  # the render process thinned it already


def _wait_for_render(end: float) -> None:
    if time.monotonic() > end:
        raise SimulationError(f"The render process gave no frame in {RENDER_TIMEOUT_S:g} s.")
    time.sleep(0.005)


def view_assets(site: RemoteSite) -> ViewAssets:
    """What the view of ``site`` draws besides its frames: the robot as the camera renders it
    (left arm at the rest pose, head forward) and the bowl's mesh."""
    stroke = float(site.kinematics.limits(RIGHT_FINGER_JOINTS).upper[0])
    fixed = {
        HEAD_PAN_JOINT: 0.0,
        **dict(zip(LEFT_ARM_JOINTS, site.config.rest_pose.left, strict=True)),
        **dict.fromkeys(LEFT_FINGER_JOINTS, 0.0),
    }
    vertices, faces = bowl_mesh(site.config.workspace.bowl)
    return ViewAssets(
        site.description.urdf_path, RIGHT_ARM_JOINTS, RIGHT_FINGER_JOINTS, stroke, fixed,
        vertices, faces,
    )  # fmt: skip


class DisplayFeed:
    """Builds, renders and delivers the display frames of one trial.

    Args:
        site: The remote site, for its camera.
        cues: The modality's AR layers.
        render: Render every camera frame (a display or wall-clock latency needs it).
        in_background: Render in the site's render process while the loop goes on (real time).
        return_delay_s: Delay of the link from the robot back to the operator (s).
        display: Where rendered frames are shown, if anywhere.
        timer: Times the ``camera``, ``point_cloud`` and ``display`` stages.
        latency: Collects the latency of each frame.
        track_every: The bowl's track is updated every this many camera frames.
        depth_aids: The frames draw the depth aids.
    """

    def __init__(
        self,
        site: RemoteSite,
        cues: ArCues,
        render: bool,
        in_background: bool,
        return_delay_s: float,
        display: Display | None,
        timer: StageTimer,
        latency: LatencyAccount,
        track_every: int = 1,
        depth_aids: bool = False,
    ) -> None:
        self._site = site
        self._depth_aids = depth_aids
        self._track_every = track_every
        self._ticks = 0
        self._track: BowlTrack | None = None
        self._marks = MarksSight()
        self._cues = cues
        self._workspace = site.config.workspace
        self._render = render
        self._background = in_background
        self._delay_s = return_delay_s
        self._display = display
        self._timer = timer
        self._latency = latency
        self._history: deque[DisplayFrame] = deque(maxlen=64)
        self._in_flight: deque[tuple[DisplayFrame, float]] = deque()  # (frame, applied sample)
        self.predicted: PredictedArm | None = None
        """The newest prediction of the arm, drawn over the frames as they reach the display."""
        self._requested: tuple[float, float, DisplayFrame] | None = None  # wall, applied, frame
        self._owed = False
        self.colocation_px: list[float] = []
        """Per camera tick, how far the ghost's gripper lands from the real one in the image."""
        self.colocation_m: list[float] = []
        """The same in space (m)."""
        self.frames_skipped = 0
        """Real time: camera ticks dropped because two came while one frame rendered or was owed."""

    def camera_tick(
        self, state: SiteState, engaged: bool, reachable: bool, applied_sample_time_s: float
    ) -> None:
        """A camera tick: the display's content now (rendered if asked), and its latency;
        ``engaged`` and ``reachable``: the status indicators then."""
        if self._ticks % self._track_every == 0 or self._track is None:
            with self._timer.stage("tracking"):
                self._track = self._site.sight_bowl()
                self._marks = self._site.sight_marks()
        self._ticks += 1
        frame = display_frame(
            state, self._track, self._site.frames, self._workspace, self._cues, engaged,
            self._site.T_cloud_true, self._depth_aids, self._marks, reachable,
        )  # fmt: skip
        self._history.append(frame)
        px, m = self._site.colocation_errors(frame.T_base_gripper[None, :3, 3])
        self.colocation_px.append(float(px[0]))
        self.colocation_m.append(float(m[0]))
        if self._background:
            if not self._site.frame_pending and self._is_new(frame.time_s):
                self._request(frame, applied_sample_time_s)
            elif self._owed:
                self.frames_skipped += 1  # two ticks while one frame is owed: drop one
            else:
                # Render it once the current frame is in, or (a base tick's poll since the last
                # physics step started the owed frame, of this same instant) once the physics
                # has moved on.
                self._owed = True
        elif self._render:
            with self._timer.stage("camera"):
                rgbd = self._site.capture()
            self._show(frame, rgbd, applied_sample_time_s)
        self._latency.frame_captured(state.time_s, applied_sample_time_s)

    def poll(self, engaged: bool, reachable: bool, applied_sample_time_s: float) -> None:
        """Real time: start the frame owed, of the site's state now, once the renderer is free
        and the physics has moved on from the last frame asked for (a base tick between two
        physics steps would render the same instant twice); show the finished frame, if any."""
        rgbd = self._site.poll_frame()
        finished = self._requested if rgbd is not None else None
        if self._owed and not self._site.frame_pending:
            state = self._site.observe()
            if self._is_new(state.time_s):
                track = self._track or self._site.sight_bowl()
                owed = display_frame(
                    state, track, self._site.frames, self._workspace, self._cues, engaged,
                    self._site.T_cloud_true, self._depth_aids, self._marks, reachable,
                )  # fmt: skip
                self._request(owed, applied_sample_time_s)
        if rgbd is None or finished is None:
            return
        requested_wall, applied, frame = finished
        self._timer.record("camera", requested_wall)
        self._show(frame, rgbd, applied, stride=1)  # the render process thinned it already

    def deliver(self, t: float) -> None:
        """Show the rendered frames whose return trip is over at ``t`` (s), each with the newest
        prediction of the arm."""
        while self._in_flight and self._in_flight[0][0].time_s + self._delay_s <= t:
            frame, applied = self._in_flight.popleft()
            if self._display is not None:
                if self.predicted is not None:
                    frame = replace(frame, predicted=self.predicted)
                with self._timer.stage("display"):
                    self._display.show(frame)
            self._latency.frame_shown(applied)

    def seen_by_operator(self, t: float) -> DisplayFrame:
        """The newest frame that has reached the operator at ``t`` (the return link's delay);
        the oldest kept one before any has."""
        for frame in reversed(self._history):
            if frame.time_s <= t - self._delay_s:
                return frame
        return self._history[0]

    @property
    def last_frame(self) -> DisplayFrame | None:
        """The newest camera frame's display content; None before the first."""
        return self._history[-1] if self._history else None

    def _is_new(self, time_s: float) -> bool:
        """No frame of the physics instant ``time_s`` (s) has been asked for yet."""
        return self._requested is None or time_s > self._requested[2].time_s

    def _request(self, frame: DisplayFrame, applied_sample_time_s: float) -> None:
        # Thinned in the render process: the display shows no more, and a quarter of the
        # pixels is a quarter of the copying and the sensor model on the loop's core.
        self._site.request_frame(CLOUD_STRIDE)
        self._requested = (time.perf_counter(), applied_sample_time_s, frame)
        self._owed = False

    def _show(
        self,
        frame: DisplayFrame,
        rgbd: RGBDFrame,
        applied_sample_time_s: float,
        stride: int = CLOUD_STRIDE,
    ) -> None:
        """Point cloud of a frame showing samples up to ``applied`` (``rgbd`` thinned by
        ``stride``), sent back to the display (:meth:`deliver` shows it once the return link's
        delay is over)."""
        with self._timer.stage("point_cloud"):
            shown = with_cloud(frame, rgbd, stride)
        # Through the return link with or without a display: the wall-clock latency counts it.
        self._in_flight.append((shown, applied_sample_time_s))

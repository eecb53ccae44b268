"""Watches the pick-and-place task and says when, and how, the trial ends (and the pointing
task, :class:`PointingMonitor`, and a person's pointing trial, :class:`SelectionMonitor`).

- Motion onset: the first control tick, once engaged, at which the operator's hand moves faster
  than ``START_SPEED_M_S``. The completion timer starts there.
- A grasp attempt is each closure of the gripper command; the bowl is grasped when both finger
  pads touch it while the gripper is closed and it has left the table: all of it, its lowest
  point ``LIFTED_M`` above the top (a grip that slips off as the arm lifts is a missed attempt,
  not a grasp, and so is a bowl tilted on the table by the fingers). It is released when the
  gripper opens after that, unless it dropped out of the closed gripper first: the fingers
  closed on nothing (``EMPTY_CLOSURE``) while the bowl was in the air (``FALLING_M``). A
  dropped bowl lies wherever it fell, and opening the empty hand to reach for it again is no
  release; a bowl set down on the table is released even if the fingers slid off it before
  they opened. Fingers that lose the bowl and, still closed, hold it again (both pads on it,
  stopped by its wall) have caught it: it is in the hand, lifted or not (seed 3's P15, trial 1,
  at 3879203: the bowl slipped 3 cm over the table as it was set down, the fingers caught it
  leaning on the table a second later, and their opening, 3 cm from the target, was scored no
  release, the trial running to its timeout).
- Placement: after the release, with the bowl at rest, the head camera's tracker looks for it
  every ``TRACKING_PERIOD_S``; the first frame in which it is found ends the trial as a success.
  A look at which the tracker's model (:class:`~arteleop.scene.BowlSight`) sees not one point of
  the bowl is not rendered: the arm hides it, and the tracker, which needs most of the bowl's
  rim, cannot find it. That saves most of the renders (about 0.2 s each at 640x480) while the
  arm goes home, and the outcome is the same (``benchmarks/bench_trials.py --ab-tracker-gate``).
- Dropped: the bowl falls below the table top.
- The other failures are named by what had happened when the time ran out or the operator
  stopped (:meth:`TaskMonitor.timed_out`, :meth:`TaskMonitor.operator_stopped`).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from arteleop.scene import BowlTrack, BowlTracker, RGBDFrame, SiteState, Workspace
from arteleop.teleop.trial import Outcome

START_SPEED_M_S = 0.05
"""Hand speed that marks the start of the reach (m/s)."""
TRACKING_PERIOD_S = 0.5
"""After the release, the bowl tracker runs on every fifteenth camera frame (2 Hz)."""
BOWL_AT_REST_M_S = 0.01
"""The bowl's centre of mass is at rest below this speed (m/s)."""
DROP_DEPTH_M = 0.05
"""A bowl this far below the table top has fallen off it (m)."""
LIFTED_M = 0.01
"""A held bowl whose lowest point is this far above the table top has been lifted: it is
grasped (m)."""
EMPTY_CLOSURE = 0.95
"""Measured closure above which the closed fingers hold nothing: the bowl's 4 mm wall stops them
at 0.82-0.90 (every hold in the default study's runs of seeds 1-3); empty, they reach 1."""
FALLING_M = 0.005
"""A bowl the closed fingers lose with its lowest point this far above the table top fell (m):
one resting on the table reads up to 1 mm (the physics' contact margin). Lower than
``LIFTED_M``: a bowl that tilts as it slips out has its low edge under ``LIFTED_M`` when the
fingers shut (the delay example's P07, trial 8: 8 mm, its centre 41 mm up)."""
SELECTED_CLOSURE = 0.05
"""Measured closure past which a pointing selection's gripper has begun to close: the
selection's moment and place."""


class TaskMonitor:
    """The task's state over one trial: onset, grasp attempts, grasp, release, placement."""

    def __init__(self, workspace: Workspace, tracker: BowlTracker) -> None:
        self._ws = workspace
        self._tracker = tracker
        self.motion_onset_s: float | None = None
        self.grasp_attempts = 0
        self.grasped = False
        self.released = False
        self.placement_error_m = float("nan")
        """Tracked bowl to target in the table's plane (m), once placed."""
        self._was_closed = False
        self._lost = False  # the closed fingers lost the bowl they held; reset when they open
        self._next_track_s = 0.0
        self.renders_skipped = 0
        """Tracker looks not rendered: the model saw none of the bowl."""

    def control(
        self, t: float, moving_hand_m_s: float | None, gripper_closed: bool, state: SiteState
    ) -> None:
        """A control tick at ``t``: ``moving_hand_m_s`` is the hand's speed while engaged (None
        before), ``gripper_closed`` the gripper command."""
        if self.motion_onset_s is None and moving_hand_m_s is not None:
            if moving_hand_m_s > START_SPEED_M_S:
                self.motion_onset_s = t
        if gripper_closed and not self._was_closed:
            self.grasp_attempts += 1
        if gripper_closed and (state.grasped or self.grasped):  # only then does lifting matter
            above_m = self._ws.bowl.lowest_z_m(state.T_base_bowl) - self._ws.table_top_z_m
            empty = state.gripper_closure > EMPTY_CLOSURE
            if state.grasped and (above_m > LIFTED_M or (self._lost and not empty)):
                self.grasped, self._lost = True, False
            elif self.grasped and above_m > FALLING_M and empty:
                self.grasped, self._lost = False, True  # out of the closed hand: a missed attempt
        if self.grasped and not gripper_closed:
            self.released = True
        if not gripper_closed:
            self._lost = False
        self._was_closed = gripper_closed

    def camera(
        self,
        t: float,
        state: SiteState,
        capture: Callable[[], RGBDFrame],
        sight: Callable[[], BowlTrack] | None = None,
    ) -> Outcome | None:
        """A camera tick at ``t``: the outcome if the trial ends now. ``capture`` renders a frame
        for the tracker (only called after the release, with the bowl at rest); ``sight``, the
        tracker's model of that instant, skips the render when it sees none of the bowl."""
        ws = self._ws
        if self.released and t >= self._next_track_s and state.bowl_speed_m_s < BOWL_AT_REST_M_S:
            self._next_track_s = t + TRACKING_PERIOD_S
            hidden = sight is not None and sight().n_points == 0
            self.renders_skipped += hidden
            track = None if hidden else self._tracker.track(capture(), ws.table_top_z_m)
            if track is not None and track.found and track.position_m is not None:
                self.placement_error_m = float(
                    np.linalg.norm(track.position_m[:2] - ws.target_m[:2])
                )
                return Outcome.SUCCESS
        if state.bowl_m[2] < ws.table_top_z_m - DROP_DEPTH_M:
            return Outcome.DROPPED
        return None

    def timed_out(self) -> Outcome:
        """The outcome of a trial whose time ran out: ``tracking_lost`` after the release (the
        tracker never found the bowl at rest), else ``timeout``."""
        return Outcome.TRACKING_LOST if self.released else Outcome.TIMEOUT

    def operator_stopped(self) -> Outcome:
        """The outcome of a trial whose operator stopped before the release: ``not_grasped``
        after closing the gripper without ever holding the bowl, else ``operator_stopped``."""
        if self.grasp_attempts and not self.grasped:
            return Outcome.NOT_GRASPED
        return Outcome.OPERATOR_STOPPED


class PointingMonitor(TaskMonitor):
    """A pointing trial's: it ends when the operator, having selected (closed the gripper),
    stops; that is a success. Whether the selection hit the target is where the gripper was
    when it closed, measured from the trace (:func:`arteleop.teleop.pointing.run_pointing_trial`),
    as a Fitts study counts a miss as a trial done, not failed."""

    def operator_stopped(self) -> Outcome:
        return Outcome.SUCCESS if self.grasp_attempts else Outcome.OPERATOR_STOPPED


class SelectionMonitor(PointingMonitor):
    """A person's pointing trial: it ends at their selection, the grip closed (the measured
    closure past :data:`SELECTED_CLOSURE`): a person says "here" by closing the grip, and does
    not stop the way a simulated participant does. Whether the movement began over the start
    cross is for the scoring to say (:func:`~arteleop.teleop.pointing.person_pointing_result`):
    a trial that went on after a closure elsewhere would leave the person waiting, not told."""

    def camera(
        self,
        t: float,
        state: SiteState,
        capture: Callable[[], RGBDFrame],
        sight: Callable[[], BowlTrack] | None = None,
    ) -> Outcome | None:
        if self.grasp_attempts and state.gripper_closure > SELECTED_CLOSURE:
            return Outcome.SUCCESS
        return super().camera(t, state, capture, sight)

"""The synthetic operator watching the display: when the gripper it shows has come to rest after
a movement, and how late the display answers the hand (the lag, learnt from it).

Nothing here knows what the display will show. The operator waits the lag it believes, timed
as people time intervals (with scalar variability), and looks once the display has shown the
gripper still over a short window, which may overlap the wait. It knows whether it made a
movement big enough to see, and does not take a display that has not answered it at all for one
at rest; but it does not know where the display will bring the gripper: a display still on the
robot's slow tail, or not yet showing a correction made in flight, is taken as settled, and the
operator looks at a stale frame. It learns the lag from the display's response half-way
through a movement: the time from its hand covering half the displacement it meant to the display
showing the gripper half-way along that way; slowly, and never from a movement too small to see.
Half-way, the movement is at its fastest, so a frame's place dates it best; the display's first
stir lags more (the robot side's filter and the arm start slowly) than the movement's middle,
over which the operator's predictions in flight reach back.
"""

from __future__ import annotations

from collections import deque

import numpy as np
from numpy.typing import NDArray

from arteleop.ar_features import DisplayFrame
from arteleop.operator.simulated.params import OperatorParams
from arteleop.operator.simulated.perception import shown_gripper_m


class DisplayWatch:
    """Where the display has shown the gripper over the last two arrival windows (None where it
    did not show it), and the lag the operator believes the display has."""

    def __init__(self, params: OperatorParams) -> None:
        self.p = params
        self._shown: deque[tuple[float, NDArray[np.float64] | None]] = deque()
        self.lag_s = params.familiar_lag_s
        """The display's lag as the operator has come to believe it (s)."""
        self._stop_s = 0.0
        self._wait_s = 0.0
        # A movement whose appearance on the display the operator watches for: from where the
        # display showed the gripper, the direction it goes on the display (a unit vector, m/m),
        # and when its hand had covered the visible displacement.
        self._awaited: tuple[NDArray[np.float64], NDArray[np.float64], float] | None = None
        # ...and, to time the display by, the half of it (m) and when the hand was half-way (s).
        self._timing: tuple[NDArray[np.float64], NDArray[np.float64], float, float] | None = None

    @property
    def latest_m(self) -> NDArray[np.float64] | None:
        """The gripper as last shown (m); None if it was not, or nothing was seen yet."""
        return self._shown[-1][1] if self._shown else None

    def see(self, time_s: float, view: DisplayFrame) -> None:
        """Keep what ``view`` shows of the gripper, once per new frame, at the operator's
        ``time_s`` (s); learn the lag if it shows an awaited movement."""
        # A prediction is of the operator's present, newer than the frame it is drawn over.
        predicted = view.shown_predicted
        stamp = view.time_s if predicted is None else predicted.time_s
        if self._shown and stamp <= self._shown[-1][0]:
            return
        cues = view.cues
        seen = cues.ghost or cues.predictive_ghost or view.gripper_in_camera
        shown = shown_gripper_m(view) if seen else None
        self._shown.append((stamp, shown))
        while self._shown and self._shown[0][0] < stamp - 2 * self.p.arrival_window_s:
            self._shown.popleft()
        if shown is None:
            return
        if self._awaited is not None:
            origin, direction, visible_at_s = self._awaited
            if self._answers(shown, origin, direction, self.p.motion_threshold_m):
                self._awaited = None
            elif time_s - visible_at_s > self.p.arrival_timeout_s:
                self._awaited = None  # never seen to move (held by the IK, out of view)
        if self._timing is not None:
            origin, direction, half_m, half_at_s = self._timing
            if self._answers(shown, origin, direction, half_m):
                sample = max(time_s - half_at_s, 0.0)
                self.lag_s += self.p.lag_learning_rate * (sample - self.lag_s)
                self._timing = None
            elif time_s - half_at_s > self.p.arrival_timeout_s:
                self._timing = None  # never seen half-way (held by the IK, out of view)

    def _answers(
        self,
        shown: NDArray[np.float64],
        origin: NDArray[np.float64],
        direction: NDArray[np.float64],
        distance_m: float,
    ) -> bool:
        """Whether the gripper ``shown`` has gone ``distance_m`` (m) from ``origin`` the way
        ``direction`` points, faster than a gripper still at rest may drift."""
        return (
            float((shown - origin) @ direction) > distance_m
            and self._speed_m_s() > self.p.arrival_speed_m_s
        )

    def _speed_m_s(self) -> float:
        """The shown gripper's mean speed over the last arrival window (m/s); 0 if unknown."""
        stamp, newest = self._shown[-1]
        past = [(ts, s) for ts, s in self._shown if ts >= stamp - self.p.arrival_window_s]
        first_s, first = past[0]
        if newest is None or first is None or stamp <= first_s:
            return 0.0
        return float(np.linalg.norm(newest - first)) / (stamp - first_s)

    def await_response(
        self, intended_m: NDArray[np.float64], visible_at_s: float, half_at_s: float
    ) -> None:
        """A movement meant to take the gripper ``intended_m`` (base frame, m) begins, its hand
        covering the visible displacement at ``visible_at_s`` (s) and half the movement at
        ``half_at_s`` (s): watch for the display to show it, and time it half-way, unless it is
        too small to see or the display does not show the gripper."""
        origin = self.latest_m
        amplitude = float(np.linalg.norm(intended_m))
        if origin is None or amplitude < 2 * self.p.motion_threshold_m:
            self._awaited = self._timing = None
            return
        direction = intended_m / amplitude
        self._awaited = (origin.copy(), direction, visible_at_s)
        self._timing = (origin.copy(), direction, 0.5 * amplitude, half_at_s)

    def hand_stopped(self, time_s: float, wait_s: float) -> None:
        """The hand stopped at ``time_s`` (s); the operator will wait ``wait_s`` (s) for the
        display to catch up (its believed lag, as it times it)."""
        self._stop_s, self._wait_s = time_s, wait_s

    def arrived(self, time_s: float) -> bool:
        """Whether, at ``time_s`` (s), the operator's wait is over, the display has answered its
        visible movement and has shown the gripper still over the arrival window; where the
        display does not show the gripper, the operator trusts its own arm after the wait and
        the window."""
        p = self.p
        waited = time_s - self._stop_s
        if waited > p.arrival_timeout_s:
            return True
        if waited < self._wait_s or self._awaited is not None:
            return False  # its wait is not over, or the display has not answered the movement
        latest = self._shown[-1][0] if self._shown else -np.inf
        window = [s for ts, s in self._shown if ts >= latest - p.arrival_window_s]
        if not self._shown or any(s is None for s in window):
            return waited >= self._wait_s + p.arrival_window_s
        if self._shown[0][0] > latest - p.arrival_window_s + 1e-9:
            return False  # not a whole window seen yet
        spread = max(float(np.linalg.norm(s - window[-1])) for s in window)
        return spread <= p.arrival_speed_m_s * p.arrival_window_s

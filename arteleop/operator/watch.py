"""The synthetic operator watching the display's gripper come to rest after a movement, and
learning the display's lag from how long that takes."""

from __future__ import annotations

from collections import deque

import numpy as np
from numpy.typing import NDArray

from arteleop.ar_features import DisplayFrame
from arteleop.operator.params import OperatorParams
from arteleop.operator.perception import shown_gripper_m


class DisplayWatch:
    """Where the display has shown the gripper over the last two arrival windows (None where it
    did not show it), and the movement the operator is waiting to see arrive."""

    def __init__(self, params: OperatorParams, hand_m: NDArray[np.float64]) -> None:
        self.p = params
        self._shown: deque[tuple[float, NDArray[np.float64] | None]] = deque()
        self.lag_s = params.familiar_lag_s
        """The display's lag as the operator has come to perceive it (s)."""
        self._stop_s = 0.0
        self._hand_at_start_m = hand_m.copy()
        self._shown_at_start_m: NDArray[np.float64] | None = None

    def began(self, hand_m: NDArray[np.float64], from_display: bool) -> None:
        """A movement begins with the hand at ``hand_m`` (m): where the display shows the
        gripper now is where it should be seen to leave from (unless not ``from_display``)."""
        self._hand_at_start_m = hand_m.copy()
        self._shown_at_start_m = self.latest_m if from_display else None

    def hand_stopped(self, time_s: float) -> None:
        self._stop_s = time_s

    def arrived(self, time_s: float, hand_m: NDArray[np.float64]) -> bool:
        """Whether the movement that left the hand at ``hand_m`` (m) is seen to have arrived at
        ``time_s`` (s); if so, the wait it took teaches the operator the lag."""
        expected_m = float(np.linalg.norm(hand_m - self._hand_at_start_m))
        if not self._arrived(time_s, expected_m):
            return False
        lag = time_s - self._stop_s - self.p.arrival_window_s
        self.lag_s = 0.5 * self.lag_s + 0.5 * max(lag, 0.0)
        return True

    @property
    def latest_m(self) -> NDArray[np.float64] | None:
        """The gripper as last shown (m); None if it was not, or nothing was seen yet."""
        return self._shown[-1][1] if self._shown else None

    def see(self, view: DisplayFrame) -> None:
        """Keep what ``view`` shows of the gripper, once per new frame."""
        # A prediction is of the operator's present, newer than the frame it is drawn over.
        predicted = view.shown_predicted
        stamp = view.time_s if predicted is None else predicted.time_s
        if self._shown and stamp <= self._shown[-1][0]:
            return
        cues = view.cues
        seen = cues.ghost or cues.predictive_ghost or view.gripper_in_camera
        self._shown.append((stamp, shown_gripper_m(view) if seen else None))
        while self._shown and self._shown[0][0] < stamp - 2 * self.p.arrival_window_s:
            self._shown.popleft()

    def _arrived(self, t: float, expected_m: float) -> bool:
        """Whether, at ``t`` (s), the display has shown the gripper still over the arrival
        window, after showing the movement made (``expected_m``, how far the hand went; m).
        Where the display does not show the gripper, the operator trusts its own arm after the
        window and the lag it believes."""
        p, stop_s, shown_at_start_m = self.p, self._stop_s, self._shown_at_start_m
        if t - stop_s > p.arrival_timeout_s:
            return True
        latest = self._shown[-1][0] if self._shown else -np.inf
        window = [s for ts, s in self._shown if ts >= latest - p.arrival_window_s]
        if not self._shown or any(s is None for s in window):
            return t - stop_s >= p.arrival_window_s + self.lag_s
        if self._shown[0][0] > latest - p.arrival_window_s + 1e-9:
            return False  # not a whole window seen yet
        spread = max(float(np.linalg.norm(s - window[-1])) for s in window)
        if spread > p.arrival_speed_m_s * p.arrival_window_s:
            return False
        if shown_at_start_m is None or expected_m < 0.01:
            return t - stop_s >= p.arrival_window_s
        shown_moved = float(np.linalg.norm(window[-1] - shown_at_start_m))
        return shown_moved >= 0.5 * expected_m

"""The synthetic operator's hand: the submovements that move it and the path it took, its
tremor, its rotation (the wrist) and its squeeze of the pinch sensor."""

from __future__ import annotations

from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray
from scipy.spatial.transform import Rotation, Slerp
from scipy.stats import chi2

from arteleop.operator.minimum_jerk import minimum_jerk_profile
from arteleop.operator.output import ALIGN, CALIBRATE

MIN_JERK_PEAK = 1.875
"""Peak speed of a minimum-jerk movement, in units of its mean speed."""
PATH_S = 2.0
"""How long the hand's own path is remembered (s): longer than any lag the operator believes."""


@dataclass(frozen=True)
class Submovement:
    """A minimum-jerk displacement of the hand (torso frame, m) from ``start_s`` (s) over
    ``duration_s`` (s); submovements under way at once superpose. ``delta_m`` is what the
    hand does, ``intended_m`` what the operator meant it to do (without the motor noise): its
    efference copy; ``scatter_m2`` the covariance (m^2) of its endpoint about it, as the
    operator knows its own movements scatter."""

    start_s: float
    delta_m: NDArray[np.float64]
    duration_s: float
    intended_m: NDArray[np.float64]
    scatter_m2: NDArray[np.float64] = field(default_factory=lambda: np.zeros((3, 3)))

    @property
    def end_s(self) -> float:
        """When the movement ends (s)."""
        return self.start_s + self.duration_s

    def share_at(self, t: float) -> float:
        """The share of the movement covered at ``t`` (s)."""
        return float(minimum_jerk_profile((t - self.start_s) / self.duration_s))

    def done_at(self, t: float) -> NDArray[np.float64]:
        """The displacement covered at ``t`` (s)."""
        return self.delta_m * self.share_at(t)

    def time_to_cover_s(self, distance_m: float) -> float:
        """When (s) the intended displacement has covered ``distance_m`` (m); its end if never."""
        amplitude = float(np.linalg.norm(self.intended_m))
        if amplitude <= distance_m:
            return self.end_s
        tau = np.linspace(0.0, 1.0, 201)
        share = minimum_jerk_profile(tau)
        return self.start_s + self.duration_s * float(np.interp(distance_m / amplitude, share, tau))


class Hand:
    """The hand's position (torso frame, m): where every finished submovement left it plus what
    those under way have covered; where the operator meant it to be (the efference copy), and
    that intended path's recent past."""

    def __init__(self, position_m: NDArray[np.float64]) -> None:
        self.position_m = position_m.copy()
        self._base = position_m.copy()
        self.intended_m = position_m.copy()
        self._intended_base = position_m.copy()
        self.moves: list[Submovement] = []
        self._finished: deque[Submovement] = deque()
        self._path: deque[tuple[float, NDArray[np.float64]]] = deque()

    @property
    def moving(self) -> bool:
        return bool(self.moves)

    def add(self, move: Submovement) -> None:
        self.moves.append(move)

    def advance(self, t: float) -> None:
        """Move the hand to where its submovements have it at ``t`` (s)."""
        done = [m for m in self.moves if t >= m.end_s]
        for m in done:
            self._base = self._base + m.delta_m
            self._intended_base = self._intended_base + m.intended_m
            self.moves.remove(m)
            self._finished.append(m)
        while self._finished and self._finished[0].end_s < t - PATH_S:
            self._finished.popleft()
        self.position_m = self._base + sum((m.done_at(t) for m in self.moves), np.zeros(3))
        self.intended_m = self._intended_base + sum(
            (m.intended_m * m.share_at(t) for m in self.moves), np.zeros(3)
        )

    def remember(self, t: float) -> None:
        """Keep the intended hand at ``t`` (s) in its recent path."""
        self._path.append((t, self.intended_m.copy()))
        while self._path[0][0] < t - PATH_S:
            self._path.popleft()

    def moved_since(self, since_s: float) -> NDArray[np.float64]:
        """How far the operator meant its hand to move since ``since_s`` (m): its efference
        copy, which knows nothing of the motor noise."""
        before = next((h for ts, h in reversed(self._path) if ts <= since_s), None)
        if before is None:  # the lag reaches back before what it remembers: the oldest
            before = self._path[0][1] if self._path else self.intended_m
        return self.intended_m - before

    def velocity_m_s(self, t: float, half_window_s: float = 0.02) -> NDArray[np.float64]:
        """How fast the operator meant its hand to move at ``t`` (s; m/s), from its efference
        copy over ``half_window_s`` (s) either side: a few samples, short beside a movement."""
        covered = self.moved_since(t - half_window_s) - self.moved_since(t + half_window_s)
        return covered / (2 * half_window_s)

    def scatter_m2(self, t: float) -> NDArray[np.float64]:
        """The covariance (m^2) of where the submovements under way at ``t`` (s) will end,
        beyond what the hand had covered of them then: their motor noise, as the operator
        knows it. Those finished since count too (``t`` is a lag in the past)."""
        moves = [*self._finished, *self.moves]
        return sum((m.scatter_m2 * (1.0 - m.share_at(t)) ** 2 for m in moves), np.zeros((3, 3)))

    def to_end(
        self, t: float, lag_s: float, timed_lag_s: float, timing_weber: float
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """How far the operator expects its hand to go at ``t`` (s) from where a display
        ``lag_s`` (s) old shows it, to the end of its movements under way: what it meant over
        ``timed_lag_s`` (s, the lag as it timed it this once) and what it still means (m);
        and the covariance (m^2) it believes that has, from its timing of the lag (SD
        ``timing_weber`` times the lag, along the way the hand went then) and its motor
        noise."""
        expected = self.moved_since(t - timed_lag_s) + self.remaining_m(t)
        then_s = t - lag_s
        timing = self.velocity_m_s(then_s) * (timing_weber * lag_s)
        cov = np.outer(timing, timing) + self.scatter_m2(then_s)
        return expected, cov

    def remaining_m(self, t: float) -> NDArray[np.float64]:
        """The intended displacement still to come from the submovements under way at ``t``
        (s; m)."""
        return sum((m.intended_m * (1.0 - m.share_at(t)) for m in self.moves), np.zeros(3))


class Tremor:
    """Physiological tremor: two sinusoids per axis (torso frame, m), their phases drawn once."""

    def __init__(
        self, amplitude_m: float, frequencies_hz: tuple[float, float], rng: np.random.Generator
    ) -> None:
        self.amplitude_m = amplitude_m
        self._w = 2 * np.pi * np.asarray(frequencies_hz)
        self._phase = rng.uniform(0, 2 * np.pi, (2, 3))

    def at(self, t: float) -> NDArray[np.float64]:
        """The tremor's displacement at ``t`` (s; m)."""
        return self.amplitude_m * np.sin(self._w[:, None] * t + self._phase).sum(axis=0) / 2


class Wrist:
    """The hand's rotation (torso frame): held in the calibration posture, turned along ``path``
    (0: that posture, 1: the working one) as the hand aligns on the gripper, at the alignment's
    minimum-jerk progress, and the working one, pitched ``hand_pitch_rad`` about the torso's y,
    from then on."""

    def __init__(self, path: Slerp, hand_pitch_rad: float) -> None:
        self._path = path
        self._work = Rotation.from_euler("y", hand_pitch_rad).as_matrix()

    def rotation(self, phase: str, hand: Hand, t: float) -> NDArray[np.float64]:
        """The (3, 3) rotation at ``t`` (s) in the operator's ``phase``, its hand ``hand``."""
        if phase == CALIBRATE:
            return np.asarray(self._path(0.0).as_matrix())
        if phase == ALIGN and hand.moving:
            m = hand.moves[0]
            progress = float(minimum_jerk_profile((t - m.start_s) / m.duration_s))
            return np.asarray(self._path(progress).as_matrix())
        return self._work


def ramped_grip(held: float, squeezed: float, t: float, ramp_end_s: float, ramp_s: float) -> float:
    """The pinch sensor at ``t`` (s), 0 open to 1 squeezed: from ``held`` to ``squeezed`` over
    the ``ramp_s`` (s) that end at ``ramp_end_s`` (s)."""
    ramp = min(1.0, (t - (ramp_end_s - ramp_s)) / ramp_s)
    return held + (squeezed - held) * ramp


def felt_apart(gap_m: NDArray[np.float64], proprioception_sd_m: float, confidence: float) -> bool:
    """Whether a person is sure its hand is ``gap_m`` (m) from where it sees what the hand moves:
    the seen place lies outside the region its proprioception places the hand in (SD
    ``proprioception_sd_m`` per axis, m) with probability ``confidence``. A gap of a few
    centimetres it cannot feel."""
    return float(gap_m @ gap_m) / proprioception_sd_m**2 > chi2.ppf(confidence, 3)


class HandMap:
    """What the operator knows of the map from its hand (torso frame, m) to the gripper it
    commands (base frame, m): ``hand_for_gripper(p)``, the hand position that commands the
    gripper at ``p``. The map is affine: the hand's step for each of the gripper's is the same
    from anywhere, and so is its inverse."""

    def __init__(self, hand_for_gripper: Callable[[NDArray[np.float64]], NDArray[np.float64]]):
        self.hand_m = hand_for_gripper
        self._origin_m = hand_for_gripper(np.zeros(3))
        steps = [hand_for_gripper(e) - self._origin_m for e in np.eye(3)]
        self.hand_per_gripper = np.column_stack(steps)
        self.gripper_per_hand = np.linalg.inv(self.hand_per_gripper)

    def gripper_m(self, hand_m: NDArray[np.float64]) -> NDArray[np.float64]:
        """The gripper the hand at ``hand_m`` commands."""
        return self.gripper_per_hand @ (hand_m - self._origin_m)

"""Smoothness of hand trajectories: normalised jerk, LDLJ, SPARC and the number of submovements;
and the share of the time the hand is still, which move-and-wait behaviour under delay raises.

Preprocessing (all four metrics): the trajectory is resampled onto a uniform time grid at its
median rate, then low-pass filtered with a zero-phase 4th-order Butterworth filter (scipy's
``filtfilt``, 6 Hz cutoff by default, the usual choice for reaching kinematics; odd extension over
three periods of the cutoff at both ends), then
differentiated with a Savitzky-Golay filter (polynomial order 5 over a 0.1 s window, polynomial
fit at both ends). Jerk peaks at a movement's start and end, where repeated central differences
are least accurate; the order-5 fit is exact there for minimum-jerk (quintic) movements.

References:
- Normalised jerk as in docs/explanation/study.md §5: J = sqrt(1/2 * integral(j(t)^2 dt) * D^5 /
  L^2).
- LDLJ and SPARC: Balasubramanian, Melendez-Calderon, Roby-Brami & Burdet, "On the analysis of
  movement smoothness", J. NeuroEng. Rehabil. 12:112 (2015); SPARC first in Balasubramanian et
  al., IEEE TBME 59(8), 2012.
- Submovements as peaks of the speed profile: Rohrer et al., "Movement smoothness changes during
  stroke recovery", J. Neurosci. 22(18), 2002.

Normalised jerk grows with a movement's duration (``D^5`` against ``L^2``: for a hand that pauses
and corrects, longer trials are "less smooth" whatever the hand did between pauses); LDLJ and
SPARC are dimensionless in duration and amplitude, and the number of submovements counts the
corrections themselves.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.signal import butter, filtfilt, find_peaks, savgol_filter

from arteleop.analysis.errors import AnalysisInputError

AXES = {"x": 0, "y": 1, "z": 2}
SG_POLYORDER = 5
SG_WINDOW_S = 0.1
STILL_SPEED_M_S = 0.05
"""Below this speed (m/s) the hand is still: the speed that starts the trial's clock
(docs/explanation/study.md §1), so that the hand before motion onset would count as still."""


def _prepare(
    time_s: ArrayLike, positions_m: ArrayLike, plane: str | Sequence[int], cutoff_hz: float | None
) -> tuple[NDArray[np.float64], NDArray[np.float64], float]:
    """Uniform time grid, selected axes, filtered positions, and the sample interval."""
    t = np.asarray(time_s, dtype=np.float64)
    p = np.asarray(positions_m, dtype=np.float64)
    if p.ndim == 1:
        p = p[:, None]
    if t.ndim != 1 or len(t) != len(p) or len(t) < 8:
        raise AnalysisInputError(
            f"need at least 8 samples with one time per position; got time {t.shape}, "
            f"positions {p.shape}"
        )
    if not np.all(np.isfinite(t)) or not np.all(np.isfinite(p)):
        raise AnalysisInputError("trajectory contains NaN or infinite values")
    if np.any(np.diff(t) <= 0):
        raise AnalysisInputError("trajectory time must increase strictly")
    axes = [AXES[a] for a in plane] if isinstance(plane, str) else list(plane)
    if p.shape[1] > 1:
        p = p[:, axes]
    dt = float(np.median(np.diff(t)))
    grid = t[0] + dt * np.arange(int(np.floor((t[-1] - t[0]) / dt + 1e-9)) + 1)
    p = np.column_stack([np.interp(grid, t, p[:, k]) for k in range(p.shape[1])])
    if cutoff_hz is not None:
        nyquist = 0.5 / dt
        if not 0 < cutoff_hz < nyquist:
            raise AnalysisInputError(f"cutoff {cutoff_hz} Hz must be in (0, {nyquist:g}) Hz")
        b, a = butter(4, cutoff_hz / nyquist)
        # Odd extension over three periods of the cutoff: shorter pads leave edge transients
        # exactly where a movement's jerk peaks.
        pad = min(len(p) - 1, 3 * int(np.ceil(1.0 / (cutoff_hz * dt))))
        p = filtfilt(b, a, p, axis=0, padtype="odd", padlen=pad)
    return grid, p, dt


def _derivative(x: NDArray[np.float64], dt: float, order: int) -> NDArray[np.float64]:
    window = max(SG_POLYORDER + 2, 2 * round(0.5 * SG_WINDOW_S / dt) + 1)
    if len(x) < window:
        raise AnalysisInputError(
            f"a trajectory of {len(x)} samples is shorter than the {window}-sample "
            "derivative window"
        )
    return savgol_filter(x, window, SG_POLYORDER, deriv=order, delta=dt, axis=0, mode="interp")


def normalized_jerk(
    time_s: ArrayLike,
    positions_m: ArrayLike,
    plane: str | Sequence[int] = "xy",
    cutoff_hz: float | None = 6.0,
) -> float:
    """Normalised jerk (dimensionless) of a trajectory; lower is smoother.

    Args:
        time_s: (N,) sample times (s).
        positions_m: (N, 3) positions (m), or (N,) / (N, k) already projected.
        plane: Axes to keep: "xy" (docs/explanation/study.md's main motion plane), "xyz", or
        indices.
        cutoff_hz: Low-pass cutoff; None skips filtering.
    """
    _, p, dt = _prepare(time_s, positions_m, plane, cutoff_hz)
    jerk = _derivative(p, dt, 3)
    duration = dt * (len(p) - 1)
    length = float(np.linalg.norm(np.diff(p, axis=0), axis=1).sum())
    if length <= 0:
        raise AnalysisInputError("the trajectory does not move: its path length is 0")
    integral = np.trapezoid(np.sum(jerk**2, axis=1), dx=dt)
    return float(np.sqrt(0.5 * integral * duration**5 / length**2))


def path_length(
    time_s: ArrayLike,
    positions_m: ArrayLike,
    plane: str | Sequence[int] = "xyz",
    cutoff_hz: float | None = 6.0,
) -> float:
    """Length (m) of a trajectory's path after the same low-pass filter as the jerk metrics.

    Summing raw sample-to-sample steps adds up sensor noise: a still hand measured through IMUs
    walks metres over a minute. The filter keeps the movement and drops that noise.
    """
    _, p, _ = _prepare(time_s, positions_m, plane, cutoff_hz)
    return float(np.linalg.norm(np.diff(p, axis=0), axis=1).sum())


def log_dimensionless_jerk(
    time_s: ArrayLike,
    positions_m: ArrayLike,
    plane: str | Sequence[int] = "xy",
    cutoff_hz: float | None = 6.0,
) -> float:
    """LDLJ from velocity (Balasubramanian et al. 2015); closer to 0 is smoother.

    ``LDLJ = -ln( D^3 / v_peak^2 * integral |d^2 v / dt^2|^2 dt )``.
    """
    _, p, dt = _prepare(time_s, positions_m, plane, cutoff_hz)
    v = _derivative(p, dt, 1)
    jerk = _derivative(v, dt, 2)
    duration = dt * (len(p) - 1)
    v_peak = float(np.max(np.linalg.norm(v, axis=1)))
    if v_peak <= 0:
        raise AnalysisInputError("the trajectory does not move: its peak speed is 0")
    integral = np.trapezoid(np.sum(jerk**2, axis=1), dx=dt)
    return float(-np.log(duration**3 / v_peak**2 * integral))


def spectral_arc_length(
    time_s: ArrayLike,
    positions_m: ArrayLike,
    plane: str | Sequence[int] = "xy",
    cutoff_hz: float | None = 6.0,
    pad_level: int = 4,
    max_frequency_hz: float = 10.0,
    amplitude_threshold: float = 0.05,
) -> float:
    """SPARC of the speed profile (Balasubramanian et al. 2015); closer to 0 is smoother.

    The speed's magnitude spectrum (zero-padded FFT, normalised to its value at 0 Hz) is cut at
    the last frequency below ``max_frequency_hz`` where it still exceeds ``amplitude_threshold``;
    SPARC is minus the arc length of that curve with frequency normalised to the cut.
    """
    _, p, dt = _prepare(time_s, positions_m, plane, cutoff_hz)
    speed = np.linalg.norm(_derivative(p, dt, 1), axis=1)
    nfft = int(2 ** (np.ceil(np.log2(len(speed))) + pad_level))
    freq = np.fft.rfftfreq(nfft, dt)
    mag = np.abs(np.fft.rfft(speed, nfft))
    if mag[0] <= 0:
        raise AnalysisInputError("the trajectory does not move: its mean speed is 0")
    mag = mag / mag[0]
    keep = freq <= max_frequency_hz
    freq, mag = freq[keep], mag[keep]
    above = np.flatnonzero(mag >= amplitude_threshold)
    freq, mag = freq[: above[-1] + 1], mag[: above[-1] + 1]
    df = np.diff(freq) / (freq[-1] - freq[0])
    return float(-np.sum(np.sqrt(df**2 + np.diff(mag) ** 2)))


def submovement_count(
    time_s: ArrayLike,
    positions_m: ArrayLike,
    plane: str | Sequence[int] = "xy",
    cutoff_hz: float | None = 6.0,
    min_prominence: float = 0.1,
) -> int:
    """Submovements (a whole number, 1 or more for a movement): peaks of the filtered speed
    that stand out by at least ``min_prominence`` of the peak speed (Rohrer et al. 2002); a
    single minimum-jerk movement has one."""
    _, p, dt = _prepare(time_s, positions_m, plane, cutoff_hz)
    speed = np.linalg.norm(_derivative(p, dt, 1), axis=1)
    top = float(speed.max())
    if top <= 0:
        raise AnalysisInputError("the trajectory does not move: its peak speed is 0")
    # Zero speed on either side, so that a peak at an end is still a peak.
    padded = np.concatenate([[0.0], speed, [0.0]])
    peaks, _ = find_peaks(padded, prominence=min_prominence * top)
    return len(peaks)


def idle_share(
    time_s: ArrayLike,
    positions_m: ArrayLike,
    plane: str | Sequence[int] = "xy",
    cutoff_hz: float | None = 6.0,
    still_m_s: float = STILL_SPEED_M_S,
) -> float:
    """The share of the time (0..1) that the hand is still, its filtered speed below
    ``still_m_s`` (m/s): waiting to see what the robot did, looking, grasping. Moving and
    waiting under delay (Ferrell 1965; Sheridan 1993) raises it.
    """
    _, p, dt = _prepare(time_s, positions_m, plane, cutoff_hz)
    speed = np.linalg.norm(_derivative(p, dt, 1), axis=1)
    return float(np.mean(speed < still_m_s))

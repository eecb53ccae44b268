"""Smoothness metrics against closed-form values of a minimum-jerk movement."""

import numpy as np
import pytest
from scipy.integrate import quad

from arteleop.analysis import log_dimensionless_jerk, normalized_jerk, spectral_arc_length
from arteleop.analysis.errors import AnalysisInputError

RATE = 100.0


def min_jerk(amplitude_m: float = 0.3, duration_s: float = 1.2, direction=(0.6, 0.8, 0.0)):
    t = np.arange(0.0, duration_s + 1e-9, 1.0 / RATE)
    tau = t / duration_s
    s = amplitude_m * (10 * tau**3 - 15 * tau**4 + 6 * tau**5)
    return t, np.outer(s, direction)


def test_normalized_jerk_of_minimum_jerk_is_sqrt_360() -> None:
    # Jerk = A / D^3 (60 - 360 tau + 360 tau^2); its squared integral is 720 A^2 / D^5, L = A.
    t, p = min_jerk()
    assert normalized_jerk(t, p, cutoff_hz=None) == pytest.approx(np.sqrt(360.0), rel=0.01)
    # Filtering at 6 Hz leaves a 1.2 s reach almost untouched.
    assert normalized_jerk(t, p) == pytest.approx(np.sqrt(360.0), rel=0.03)


def test_normalized_jerk_is_scale_and_duration_invariant() -> None:
    a = normalized_jerk(*min_jerk(0.1, 0.8), cutoff_hz=None)
    b = normalized_jerk(*min_jerk(0.5, 2.0), cutoff_hz=None)
    assert a == pytest.approx(b, rel=0.02)


def test_ldlj_of_minimum_jerk() -> None:
    # v_peak = 1.875 A / D, so D^3 / v_peak^2 * 720 A^2 / D^5 = 720 / 1.875^2.
    t, p = min_jerk()
    assert log_dimensionless_jerk(t, p, cutoff_hz=None) == pytest.approx(
        -np.log(720 / 1.875**2), abs=0.02
    )


def _sparc_reference(duration_s: float) -> float:
    """SPARC from the continuous Fourier transform of the minimum-jerk speed profile."""

    def speed(t: float) -> float:
        tau = t / duration_s
        return 30.0 / duration_s * (tau**2 - 2 * tau**3 + tau**4)

    def magnitude(f: float) -> float:
        w = 2 * np.pi * f
        re = quad(lambda t: speed(t) * np.cos(w * t), 0, duration_s)[0]
        im = quad(lambda t: speed(t) * np.sin(w * t), 0, duration_s)[0]
        return float(np.hypot(re, im))

    freq = np.linspace(0.0, 10.0, 4001)
    mag = np.array([magnitude(f) for f in freq]) / magnitude(0.0)
    last = np.flatnonzero(mag >= 0.05)[-1]
    freq, mag = freq[: last + 1], mag[: last + 1]
    return float(-np.sum(np.hypot(np.diff(freq) / (freq[-1] - freq[0]), np.diff(mag))))


def test_sparc_of_minimum_jerk_matches_the_continuous_spectrum() -> None:
    t, p = min_jerk(duration_s=1.2)
    assert spectral_arc_length(t, p, cutoff_hz=None) == pytest.approx(
        _sparc_reference(1.2), abs=0.02
    )


@pytest.mark.parametrize(
    "metric, worse",
    [
        (normalized_jerk, lambda clean, bad: bad > clean),
        (log_dimensionless_jerk, lambda clean, bad: bad < clean),
        (spectral_arc_length, lambda clean, bad: bad < clean),
    ],
)
def test_tremor_and_submovements_make_each_metric_worse(metric, worse) -> None:
    t, p = min_jerk(duration_s=1.5)
    clean = metric(t, p)
    tremor = p + 0.002 * np.sin(2 * np.pi * 4.0 * t)[:, None] * np.array([0.0, 1.0, 0.0])
    # A corrective sub-movement: stop short, then a second small minimum-jerk segment.
    t2, p_main = min_jerk(0.27, 1.2)
    _, p_fix = min_jerk(0.03, 0.5)
    sub_t = np.concatenate([t2, t2[-1] + 1 / RATE + np.arange(len(p_fix)) / RATE])
    sub_p = np.vstack([p_main, p_main[-1] + p_fix])
    assert worse(clean, metric(t, tremor))
    assert worse(metric(*min_jerk(0.3, sub_t[-1])), metric(sub_t, sub_p))


def test_plane_selection() -> None:
    t, p = min_jerk(direction=(0.0, 0.0, 1.0))  # purely vertical
    with pytest.raises(AnalysisInputError, match="path length is 0"):
        normalized_jerk(t, p)  # nothing moves in x-y
    assert normalized_jerk(t, p, plane="xyz", cutoff_hz=None) == pytest.approx(
        np.sqrt(360), rel=0.01
    )


def test_bad_trajectories() -> None:
    t, p = min_jerk()
    with pytest.raises(AnalysisInputError, match="time must increase"):
        normalized_jerk(t[::-1], p)
    p = p.copy()
    p[5, 0] = np.nan
    with pytest.raises(AnalysisInputError, match="NaN"):
        normalized_jerk(t, p)

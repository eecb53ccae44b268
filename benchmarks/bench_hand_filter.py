"""Jitter and lag of the robot side's hand filter (the 1€ filter), with and without it.

A hand held still, moved 0.3 m in a minimum-jerk reach and held still again is worn with the
simulated wearable (its default noise, drift and losses) and reconstructed as the controller
does; the reconstructed hand then goes through the filter. Per seed it measures:

- **jitter at rest**: the median step of the hand from one sample to the next (mm per 10 ms)
  over the last still second: what the arm would copy, and what a watcher sees as the gripper
  never coming to rest (slow drift of the IMUs is not jitter, and no filter removes it);
- **lag in motion**: the time shift (ms) that best aligns the filtered hand with the
  unfiltered one over the reach (1 ms steps), the delay the filter adds to the command;
- **path offset**: the filtered hand's mean minus the unfiltered one's over the last still
  second (mm): the filter must not move where the hand rests.

Casiez et al. (CHI 2012) tune the minimum cutoff at rest for jitter, then beta in fast motion for
lag; the grid below shows both. The default is the first row after "off".

    python benchmarks/bench_hand_filter.py [--seeds 5]
"""

from __future__ import annotations

from arteleop import blas_kernel  # noqa: F401  (first: it picks numpy's BLAS kernel)

# isort: split
import argparse
import sys

import numpy as np
from scipy.spatial.transform import Rotation

from arteleop.operator import RecordingInfo, WearableConfig, minimum_jerk, record_hand_motion
from arteleop.teleop import HandFilterConfig, filter_hand_path, reconstruct

RATE_HZ = 100.0
START = np.array([0.30, -0.22, -0.28])
END = np.array([0.50, -0.02, -0.12])
STILL_S, REACH_S = 1.5, 0.8


def hand_motion() -> tuple[np.ndarray, np.ndarray]:
    """(time_s, hand_m) of the still-reach-still motion at the wearable's rate."""
    still = int(STILL_S * RATE_HZ)
    t_reach = np.arange(0.0, REACH_S, 1.0 / RATE_HZ)
    hand = np.vstack([np.tile(START, (still, 1)), minimum_jerk(START, END, REACH_S, t_reach),
                      np.tile(END, (still, 1))])  # fmt: skip
    return np.arange(len(hand)) / RATE_HZ, hand


def measure(config: HandFilterConfig, seed: int) -> dict[str, float]:
    _, hand = hand_motion()
    rotations = Rotation.from_euler("y", np.full((len(hand), 1), 0.4))
    info = RecordingInfo(rate_hz=RATE_HZ)
    rec = record_hand_motion(hand, rotations, np.zeros(len(hand)), info, WearableConfig(),
                             np.random.default_rng(seed))  # fmt: skip
    raw = reconstruct(rec.recording)
    filtered, _ = filter_hand_path(config, raw.time_s, raw.hand_m, raw.hand_quat_wxyz)
    t = raw.time_s
    end = t[-1]
    rest = t >= end - 1.0
    jitter = lambda p: float(np.median(np.linalg.norm(np.diff(p[rest], axis=0), axis=1)))  # noqa: E731
    reach_start = end - STILL_S - REACH_S
    moving = (t >= reach_start) & (t <= reach_start + REACH_S + 0.2)
    shifts = np.arange(0.0, 0.2, 0.001)
    errors = [np.mean([np.sum((np.interp(t[moving] - s, t, raw.hand_m[:, k])
                               - filtered[moving, k]) ** 2) for k in range(3)])
              for s in shifts]  # fmt: skip
    return {
        "jitter_raw_mm": 1000 * jitter(raw.hand_m),
        "jitter_mm": 1000 * jitter(filtered),
        "lag_ms": 1000 * float(shifts[int(np.argmin(errors))]),
        "offset_mm": 1000
        * float(np.linalg.norm(filtered[rest].mean(0) - raw.hand_m[rest].mean(0))),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--seeds", type=int, default=5)
    args = parser.parse_args()
    if args.seeds < 1:
        sys.exit(f"--seeds {args.seeds}: give 1 or more.")
    default = HandFilterConfig()
    grid = [("off", HandFilterConfig(enabled=False)), ("default", default)] + [
        (f"min {m:g} Hz, beta {b:g}", HandFilterConfig(min_cutoff_hz=m, beta_per_m=b))
        for m in (0.5, 1.0, 2.0) for b in (0.0, 2.0, 5.0, 20.0)
        if (m, b) != (default.min_cutoff_hz, default.beta_per_m)
    ]  # fmt: skip
    print(
        f"## The hand filter, medians over {args.seeds} seeds (unfiltered hand as the baseline)\n"
    )
    print(
        "| filter | jitter at rest (mm per sample) | ratio to unfiltered | lag in motion (ms) | rest offset (mm) |"
    )
    print("| --- | ---: | ---: | ---: | ---: |")
    for name, config in grid:
        rows = [measure(config, seed) for seed in range(args.seeds)]
        med = {k: float(np.median([r[k] for r in rows])) for k in rows[0]}
        print(f"| {name} | {med['jitter_mm']:.2f} | {med['jitter_mm'] / med['jitter_raw_mm']:.2f} "
              f"| {med['lag_ms']:.0f} | {med['offset_mm']:.2f} |")  # fmt: skip


if __name__ == "__main__":
    main()

"""Hand motions made inside the tests: a reach out and back, as a pick-and-place would start."""

from __future__ import annotations

import numpy as np
from scipy.spatial.transform import Rotation

from arteleop.operator import (
    ImuErrorConfig,
    RecordingInfo,
    SynthesizedRecording,
    WearableConfig,
    minimum_jerk,
    record_hand_motion,
)

START = np.array([0.30, -0.22, -0.28])
FAR = np.array([0.50, -0.02, -0.12])


def reach_and_return(
    seed: int = 0,
    errors: ImuErrorConfig | None = None,
    heading_rad: float = 0.0,
    duration_s: float = 1.5,
) -> SynthesizedRecording:
    rate = 100.0
    t = np.arange(0.0, duration_s, 1.0 / rate)
    out = minimum_jerk(START, FAR, duration_s, t)
    back = minimum_jerk(FAR, START, duration_s, t)
    hand = np.vstack([out, back])
    tilt = np.concatenate([np.linspace(0.0, 0.6, len(t)), np.linspace(0.6, 0.0, len(t))])
    rotations = Rotation.from_euler("y", 0.4) * Rotation.from_euler("x", tilt[:, None])
    grip = np.concatenate([np.zeros(len(t)), np.ones(len(t))])
    wearable = WearableConfig(errors=errors or ImuErrorConfig(), torso_heading_rad=heading_rad)
    info = RecordingInfo(rate_hz=rate)
    if heading_rad:
        from dataclasses import replace

        info = replace(info, calibration=replace(info.calibration, torso_heading_rad=heading_rad))
    return record_hand_motion(hand, rotations, grip, info, wearable, np.random.default_rng(seed))

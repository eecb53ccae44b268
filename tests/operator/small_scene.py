"""A small scene for the operator's mechanism: no simulator, a gripper that follows the hand
(mapped one to one) after a lag, shown in display frames built by hand."""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass, replace

import numpy as np

from arteleop.ar_features import ArCues
from arteleop.operator import (
    ArmModel,
    CalibrationPosture,
    OperatorParams,
    OperatorTraits,
    PickAndPlace,
    SyntheticOperator,
)
from arteleop.transforms import make_transform
from tests.ar_features.frames import display_frame

BOWL_M = np.array([0.68, -0.45, -0.2])
GRASP_OFFSET_M = np.array([0.0, 0.078, 0.055])
GRASP_M = BOWL_M + GRASP_OFFSET_M


@dataclass(frozen=True)
class Descent:
    """How one descent onto the grasp point went."""

    duration_s: float
    looks: int
    corrections: int
    error_m: float
    overshoot_m: float


def descend(
    cues: ArCues,
    seed: int,
    traits: OperatorTraits | None = None,
    lag_s: float = 0.0,
    params: OperatorParams | None = None,
    start_above_m: float = 0.10,
    limit_s: float = 30.0,
    start_beside_m: float = 0.0,
    reach_x_m: float = np.inf,
    notice: bool = True,
) -> Descent:
    """The operator's descent from ``start_above_m`` over the grasp point (and ``start_beside_m``
    beyond it along x) until it accepts, the display showing the gripper ``lag_s`` (s) late, at
    30 frames/s. The arm reaches no further than ``reach_x_m`` along x, and stops there: with
    ``notice`` the display says so (:attr:`DisplayFrame.reachable`)."""
    params = params or OperatorParams(familiar_lag_s=lag_s)
    task = PickAndPlace(GRASP_OFFSET_M, np.array([0.3, -0.56, 0.0]))
    rng = np.random.default_rng(seed)
    traits = replace(traits or OperatorTraits(), bias_seed=seed)
    op = SyntheticOperator(task, lambda p: p, ArmModel(), CalibrationPosture(), rng, params,
                           traits)  # fmt: skip
    start = GRASP_M + [start_beside_m, 0.0, start_above_m]
    op.start_phase("descend", start, 0.0)
    history: deque[tuple[float, np.ndarray]] = deque([(-1.0, start.copy())])
    view, lowest, t = None, start[2], 0.0
    while op.phase == "descend" and t < limit_s:
        shown = next(h for ts, h in reversed(history) if ts <= t - lag_s).copy()
        short = shown[0] > reach_x_m
        shown[0] = min(shown[0], reach_x_m)
        if view is None or t - view.time_s >= 1 / 30 - 1e-9:
            view = display_frame(
                cues=cues,
                time_s=t,
                bowl_m=BOWL_M,
                T_base_gripper=make_transform(np.diag([1.0, -1.0, -1.0]), shown),
                reachable=not (notice and short),
            )
        lowest = min(lowest, float(op.hand.position_m[2]))
        op.step(t, view)
        history.append((t, op.hand.position_m.copy()))
        t = round(t + 0.01, 10)
    return Descent(
        t,
        op.looks_total,
        op.corrections_total,
        float(np.linalg.norm(op.hand.position_m - GRASP_M)),
        max(GRASP_M[2] - lowest, 0.0),
    )

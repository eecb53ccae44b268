"""One Fitts pointing trial through the whole loop: the simulated participant's calibration task
(docs/explanation/operator-model.md, ``benchmarks/bench_fitts.py``).

Targets are circles drawn on the table, ``distance_m`` along +y from a start point drawn as a
cross, their diameter ``width_m``; the bowl waits out of the way. The trial ends when the
operator has selected (closed the gripper).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from arteleop.errors import SimulationError
from arteleop.operator import OperatorParams, OperatorTraits, SyntheticSource
from arteleop.robot.grip_control import GripHysteresis
from arteleop.robot.mapping import HandToGripper
from arteleop.scene import RemoteSite, SiteConfig, Workspace
from arteleop.teleop.loop import run_trial
from arteleop.teleop.network import NetworkConfig
from arteleop.teleop.task_monitor import SELECTED_CLOSURE, START_SPEED_M_S
from arteleop.teleop.trial import TrialConfig
from arteleop.teleop.trial_task import pointing_task

POINTING_START_XY_M = (0.68, -0.55)
"""Where each pointing movement starts (over the table, m); targets lie along +y from it."""
START_RADIUS_M = 0.02
"""A person's pointing movement starts over the start cross: the gripper within this of its
middle in the table's plane (m): a fifth of the default design's shortest distance (0.1 m); a
design's targets nearer than twice this overlap the start's region, where the movement's start
is less sure."""
BOWL_AWAY_XY_M = (0.45, -0.65)
"""The bowl, out of the pointing path and in the arm's reach (the site checks both)."""


@dataclass(frozen=True)
class PointingResult:
    """How one pointing trial went; NaN where the operator never selected.

    The selection is the closure the operator decided: the gripper's place when, after the
    decision, its closure first passes :data:`SELECTED_CLOSURE`. A closure before the decision is
    a slip (the fingers pushed against the table during a movement), counted and not taken for
    the selection.

    Attributes:
        movement_time_s: From the start of the pointing movement to the decision to select (s).
        along_m: The gripper at the selection past the target's centre along the task axis (m).
        across_m: ...and across it, in the table's plane (m).
        hit: The gripper was within the circle at the selection.
        slips: Closures before the decision.
        believed_lag_s: The display's lag as the operator believed it at the trial's end (s):
            what it brings to its next trial under the same lag.
        activity_s: Where the movement time went: the seconds the operator spent in each of
            :data:`~arteleop.operator.ACTIVITIES` (they add up to ``movement_time_s``).
        corrections: Submovements after the pointing movement's first, in flight or after a
            look.
        looks: Looks begun during the movement time.
    """

    movement_time_s: float
    along_m: float
    across_m: float
    hit: bool
    slips: int = 0
    believed_lag_s: float = float("nan")
    activity_s: Mapping[str, float] = field(default_factory=dict)
    corrections: int = 0
    looks: int = 0

    @property
    def selected(self) -> bool:
        return bool(np.isfinite(self.movement_time_s))


def run_pointing_trial(
    distance_m: float,
    width_m: float,
    traits: OperatorTraits,
    seed: int,
    round_trip_lag_s: float = 0.0,
    timeout_s: float = 40.0,
    params: OperatorParams | None = None,
    depth_aids: bool = False,
) -> PointingResult:
    """A pointing trial at a target ``distance_m`` away and ``width_m`` wide (m), by a person
    with ``traits`` and the operator's constants ``params`` (the defaults; a person who has
    practised a lag brings its belief as ``familiar_lag_s``), with ``round_trip_lag_s`` (s) of
    network delay, half each way; the display draws the depth aids if ``depth_aids``."""
    config = pointing_config(distance_m, width_m, seed, round_trip_lag_s, timeout_s, depth_aids)
    ws = config.site.workspace
    with RemoteSite(config.site) as site:
        source = pointing_source(config, site.observe().gripper_m, traits, params=params)
        result = run_trial(source, config, site)
    believed_lag_s = source.operator.lag_s
    trace = result.trace
    if trace is None:
        raise SimulationError("The pointing trial recorded no trace although its config asked.")
    pointing = [r for r in source.operator.history if r.name == "point"]
    if not pointing or pointing[0].first_move_s is None or pointing[0].end_s is None:
        _, slips = decided_selection(trace["time_s"], trace["gripper_closure"], np.inf)
        return PointingResult(float("nan"), float("nan"), float("nan"), False, slips,
                              believed_lag_s)  # fmt: skip
    decided_s = pointing[0].end_s
    k, slips = decided_selection(trace["time_s"], trace["gripper_closure"], decided_s)
    off = np.array([trace["gripper_x_m"][k], trace["gripper_y_m"][k]]) - ws.target_m[:2]
    return PointingResult(
        decided_s - pointing[0].first_move_s,
        float(off[1]),
        float(off[0]),
        bool(np.linalg.norm(off) <= width_m / 2),
        slips,
        believed_lag_s,
        dict(pointing[0].activity_s),
        pointing[0].corrections,
        pointing[0].looks,
    )


def person_pointing_result(
    trace: Mapping[str, NDArray[np.float64]], workspace: Workspace
) -> PointingResult:
    """A person's pointing trial (:class:`~arteleop.teleop.task_monitor.SelectionMonitor`)
    scored from its trace and ``workspace``: NaN where there was no selection, or where the
    gripper had not been over the start cross (:data:`START_RADIUS_M`) before it, a movement
    whose distance is not the design's.

    The selection is the grip's first closing (the grip received reaching
    :class:`~arteleop.robot.grip_control.GripHysteresis`'s ``close_at``); its place is the
    gripper's where the measured closure then first passes :data:`SELECTED_CLOSURE`, as a
    simulated participant's is. The movement starts at the gripper's last tick still (below
    ``START_SPEED_M_S``) over the cross before it, or as it came over the cross if it never
    stood still there. Both ends are where the site sees them, a network delay after the person
    acted: the movement time is the person's, the gripper's tracking lag aside."""
    t, closure = trace["time_s"], trace["gripper_closure"]
    xy = np.column_stack([trace["gripper_x_m"], trace["gripper_y_m"]])
    rises = _rises(np.nan_to_num(trace["grip"]) >= GripHysteresis().close_at)
    over = np.linalg.norm(xy - np.asarray(workspace.start_xy_m), axis=1) <= START_RADIUS_M
    nan = float("nan")
    if not len(rises) or not over[: rises[0] + 1].any():
        return PointingResult(nan, nan, nan, False)
    s = rises[0]
    k, _ = decided_selection(t, closure, t[s])
    last_over = np.flatnonzero(over[: s + 1])[-1]
    back = over[last_over::-1]  # from there back to the trial's start
    entered = last_over + 1 - (int(np.argmin(back)) if not back.all() else len(back))
    speed = np.concatenate([[0.0], np.linalg.norm(np.diff(xy, axis=0), axis=1) / np.diff(t)])
    still = np.flatnonzero(speed[entered : last_over + 1] <= START_SPEED_M_S)
    onset = min(entered + (still[-1] if len(still) else 0), s)
    off = xy[k] - np.asarray(workspace.target_xy_m)
    hit = bool(np.linalg.norm(off) <= workspace.target_circle_radius_m)
    return PointingResult(float(t[s] - t[onset]), float(off[1]), float(off[0]), hit)


def pointing_config(
    distance_m: float,
    width_m: float,
    seed: int,
    round_trip_lag_s: float = 0.0,
    timeout_s: float = 40.0,
    depth_aids: bool = False,
) -> TrialConfig:
    """The trial of a pointing movement ``distance_m`` long at a target ``width_m`` wide (m),
    under ``round_trip_lag_s`` (s) of network delay, half each way, the depth aids drawn if
    ``depth_aids``; its trace recorded."""
    target_xy = (POINTING_START_XY_M[0], POINTING_START_XY_M[1] + distance_m)
    ws = Workspace(start_xy_m=POINTING_START_XY_M, target_xy_m=target_xy,
                   bowl_xy_m=BOWL_AWAY_XY_M, target_circle_radius_m=width_m / 2,
                   marker_line_width_m=width_m / 4)  # fmt: skip
    return TrialConfig(modality="none", seed=seed, timeout_s=timeout_s,
                       network=NetworkConfig(delay_s=round_trip_lag_s / 2),
                       site=SiteConfig(workspace=ws), record_trace=True,
                       depth_aids=depth_aids, task="pointing")  # fmt: skip


def pointing_source(
    config: TrialConfig,
    rest_gripper_m: NDArray[np.float64],
    traits: OperatorTraits,
    source_type: type[SyntheticSource] = SyntheticSource,
    params: OperatorParams | None = None,
) -> SyntheticSource:
    """The person with ``traits`` (and the operator's constants ``params``) doing the pointing
    task of ``config`` (from :func:`pointing_config`), the gripper resting at
    ``rest_gripper_m`` (base frame, m), as a ``source_type`` (a :class:`SyntheticSource`, or one
    that also records what it saw)."""
    task = pointing_task(config.site.workspace, rest_gripper_m)
    to_hand = HandToGripper(config.controller.mapping).hand_position_for
    rng = np.random.default_rng([config.seed, 1])
    return source_type(task, to_hand, rng, params=params, traits=traits)


def decided_selection(
    time_s: NDArray[np.float64], closure: NDArray[np.float64], decided_s: float
) -> tuple[int, int]:
    """The tick of the selection decided at ``decided_s`` (s): where the gripper's closure first
    rises past :data:`SELECTED_CLOSURE` from then on (or is already past it, with none rising
    later; the last tick if it never closes); and the slips, closures that rose before."""
    closed = closure > SELECTED_CLOSURE
    rises = _rises(closed)
    later = rises[time_s[rises] >= decided_s]
    held = np.flatnonzero(closed & (time_s >= decided_s))
    k = later[0] if len(later) else held[0] if len(held) else len(time_s) - 1
    return int(k), int(np.sum(time_s[rises] < decided_s))


def _rises(on: NDArray[np.bool_]) -> NDArray[np.intp]:
    """The ticks at which ``on`` turns true (the first too, if it begins true)."""
    return np.flatnonzero(on & ~np.concatenate([[False], on[:-1]]))

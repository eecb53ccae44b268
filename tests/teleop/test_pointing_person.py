"""A person's pointing trial (a served pointing study): it ends at their selection, and is
scored where the gripper closed, from when it left the start cross."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from arteleop.operator import HandTarget, live_source
from arteleop.scene import RemoteSite
from arteleop.teleop import PERSON_POINTING, Outcome, TrialProgress, run_trial
from arteleop.teleop.pointing import person_pointing_result, pointing_config

LAG_S = 0.1
"""The trial's round trip (s)."""
OFF_XY_M = np.array([0.012, -0.006])
"""Where the person puts the gripper, from the target's middle (x across, y along; m)."""


def test_a_persons_pointing_trial_ends_at_their_selection_and_is_scored_where_it_closed() -> None:
    """Engaged, the person waits over the cross, moves 12 mm across and 6 mm short of the
    target's middle 3 s later and closes the grip 3 s after that: the trial ends then, the
    selection where the gripper was, the movement time from leaving the cross to the grip (both
    seen a one-way delay late, so the same 3 s)."""
    config = replace(pointing_config(0.1, 0.04, 0, LAG_S, 30.0), task=PERSON_POINTING)
    ws = config.site.workspace
    above_m = ws.table_top_z_m + 0.06
    with RemoteSite(config.site) as site:
        rest = site.observe().gripper_m
        target = HandTarget(rest)
        engaged: list[float] = []

        def tick(status: TrialProgress) -> None:
            if status.engaged and not engaged:
                engaged.append(status.time_s)
                target.set(gripper_m=[*ws.start_xy_m, above_m])
            if not engaged:
                return
            t = status.time_s - engaged[0]
            if 3.0 <= t < 6.0:
                target.set(gripper_m=[*(np.asarray(ws.target_xy_m) + OFF_XY_M), above_m])
            elif t >= 6.0:
                target.set(grip=1.0)

        source = live_source(target, config.controller.mapping, 0)
        result = run_trial(source, config, site, None, tick)
    assert result.outcome is Outcome.SUCCESS
    assert result.duration_s < engaged[0] + 6.0 + 1.0, "ended as the gripper closed"
    assert result.trace is not None
    scored = person_pointing_result(result.trace, ws)
    assert scored.selected and scored.hit
    # Where the gripper stood as it closed (the wearable's hand is a few mm off the target set).
    trace = result.trace
    stood = np.array([trace["gripper_x_m"][-1], trace["gripper_y_m"][-1]]) - ws.target_xy_m
    assert np.allclose([scored.across_m, scored.along_m], stood, atol=0.001)
    assert np.allclose(stood, OFF_XY_M, atol=0.008)
    assert 2.9 < scored.movement_time_s < 3.05, scored.movement_time_s


def test_a_gripper_that_passes_over_the_cross_starts_its_movement_as_it_enters() -> None:
    """Never still over the cross: the movement starts where the gripper came over it. A grip
    closed before the gripper was over the cross, or never, counts no selection."""
    ws = pointing_config(0.1, 0.04, 0).site.workspace
    t = np.arange(0.0, 4.0, 0.01)
    x0, y0 = ws.start_xy_m
    y = y0 - 0.1 + 0.1 * t  # 10 cm/s along +y: over the cross (2 cm) from 0.8 s
    closed = (t >= 2.5).astype(float)
    trace = {"time_s": t, "gripper_x_m": np.full_like(t, x0), "gripper_y_m": y,
             "grip": closed, "gripper_closure": np.clip(10 * (t - 2.55), 0, 1)}  # fmt: skip
    scored = person_pointing_result(trace, ws)
    assert abs(scored.movement_time_s - (2.5 - 0.81)) < 0.011, scored.movement_time_s
    assert abs(scored.along_m - (y0 - 0.1 + 0.1 * 2.56 - ws.target_xy_m[1])) < 1e-3
    assert not scored.hit
    never = {**trace, "grip": np.zeros_like(t)}
    assert not person_pointing_result(never, ws).selected
    early = {**trace, "grip": ((t >= 0.5) & (t < 0.6) | (t >= 2.5)).astype(float)}
    assert not person_pointing_result(early, ws).selected

"""Live teleoperation: a person driving the gripper's target, and the application that runs
trial after trial in the browser."""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Iterator
from dataclasses import replace

import numpy as np
import pytest

from arteleop.ar_features import DisplayFrame, ViewConfig
from arteleop.operator import HandTarget, live_source
from arteleop.scene import HeadCameraConfig, RemoteSite, SiteConfig
from arteleop.teleop import (
    Outcome,
    TeleopApp,
    TeleopAppConfig,
    TrialConfig,
    TrialProgress,
    run_trial,
)
from arteleop.teleop.live_app import READY


def _drive(site: RemoteSite, offset_m: np.ndarray, duration_s: float) -> list[TrialProgress]:
    """Engage at rest, then move the target by ``offset_m``; the statuses of the trial."""
    rest = site.observe().gripper_m
    target = HandTarget(rest)
    config = TrialConfig(timeout_s=duration_s, seed=0)
    seen: list[TrialProgress] = []

    def tick(status: TrialProgress) -> None:
        if status.engaged and not any(s.engaged for s in seen):
            target.set(gripper_m=rest + offset_m, grip=1.0)
        seen.append(status)

    result = run_trial(live_source(target, config.controller.mapping, 0), config, site, None, tick)
    assert result.outcome is Outcome.TIMEOUT
    # The display frame carries the notice the page shows (no delay: the same camera tick's).
    assert result.final_frame is not None
    assert result.final_frame.reachable == seen[-1].reachable
    return seen


def test_the_gripper_follows_the_dragged_target(site: RemoteSite) -> None:
    rest = site.observe().gripper_m
    offset = np.array([0.10, 0.05, 0.08])
    seen = _drive(site, offset, duration_s=9.0)
    engaged_s = next(s.time_s for s in seen if s.engaged)
    assert engaged_s < 4.0  # calibration hold, alignment, engagement
    state = site.observe()
    assert np.linalg.norm(state.gripper_m - (rest + offset)) < 0.015
    assert state.gripper_closure > 0.9  # the grip slider closed it
    assert seen[-1].reachable


def test_a_target_moved_before_the_robot_engages_is_where_the_gripper_goes(
    site: RemoteSite,
) -> None:
    # A key pressed as the trial began moved the target before the hand had aligned: the robot
    # did not engage until the person moved it back, and the page said only to wait.
    rest = site.observe().gripper_m
    target = HandTarget(rest)
    config = TrialConfig(timeout_s=8.0, seed=0)
    source = live_source(target, config.controller.mapping, 0)  # as Start is pressed
    target.set(gripper_m=rest + [0.08, 0.0, 0.0])  # the first input, at once
    seen: list[TrialProgress] = []
    run_trial(source, config, site, None, seen.append)
    engaged_s = next(s.time_s for s in seen if s.engaged)
    assert engaged_s < 4.0
    assert not any(not s.reachable for s in seen)  # no reach warning: nothing is out of reach
    assert np.linalg.norm(site.observe().gripper_m - (rest + [0.08, 0.0, 0.0])) < 0.015


def test_a_target_out_of_reach_stops_the_arm_at_the_nearest_pose(site: RemoteSite) -> None:
    rest = site.observe().gripper_m
    far = np.array([1.5, 0.0, 0.0])  # 1.5 m further: beyond the arm's reach
    seen = _drive(site, far, duration_s=8.0)
    assert not any(s.reachable for s in seen[-30:])  # the last second
    gripper = site.observe().gripper_m
    # Stretched towards the target, short of it.
    assert gripper[0] > rest[0] + 0.15
    assert np.linalg.norm(gripper - (rest + far)) > 0.5


def _until(condition: Callable[[], bool], timeout_s: float = 15.0) -> bool:
    end = time.monotonic() + timeout_s
    while not condition():
        if time.monotonic() > end:
            return False
        time.sleep(0.05)
    return True


@pytest.fixture
def app(site_config: SiteConfig) -> Iterator[TeleopApp]:
    small = replace(site_config, camera=HeadCameraConfig(width_px=160, height_px=120))
    trial = TrialConfig(timeout_s=2.0, seed=4, site=small)
    config = TeleopAppConfig("synthetic", trial, ViewConfig(port=0), pause_s=0.2)
    with RemoteSite(small) as site, TeleopApp(config, site) as running:
        yield running


def test_the_app_runs_trial_after_trial_with_the_next_seed(app: TeleopApp) -> None:
    done = threading.Event()

    def on_trial(result: object) -> None:
        if len(app.results) == 2:
            app.stop()
            done.set()

    runner = threading.Thread(target=app.run, args=(on_trial,))
    runner.start()
    assert done.wait(timeout=30.0)
    runner.join(timeout=5.0)
    assert not runner.is_alive()
    assert [r.seed for r in app.results] == [4, 5]
    assert all(r.outcome is Outcome.TIMEOUT for r in app.results)
    assert app.panel._last.value == "seed 5: timeout after 2 s"


def test_reset_stops_the_trial_and_waits_for_start(app: TeleopApp) -> None:
    """...and the view shows the robot at rest when the panel says so, not the stopped
    trial's last frame."""
    shown: list[DisplayFrame] = []
    show = app.view.show
    app.view.show = lambda frame: (shown.append(frame), show(frame))  # type: ignore[method-assign]
    rest_m = app.site.observe().gripper_m
    runner = threading.Thread(target=app.run)
    runner.start()
    try:
        assert _until(lambda: len(shown) > 3 and shown[-1].time_s > 0.0)  # the first trial runs
        app.reset()
        assert _until(lambda: app.panel._state.value == "at the rest pose: press Start trial")
        assert shown[-1].time_s == 0.0 and shown[-1].has_cloud
        np.testing.assert_allclose(shown[-1].gripper_m, rest_m, atol=1e-3)
        threading.Event().wait(0.5)
        assert app.results == []  # interrupted, not finished
        assert app.site.time_s == 0.0  # and no trial has started since
    finally:
        app.stop()
        runner.join(timeout=5.0)
    assert not runner.is_alive()


def test_a_persons_first_trial_waits_for_start(site_config: SiteConfig) -> None:
    """With a person at the controls no trial starts when the server does (before anyone has
    the page open): the panel asks for Start, and Start runs the trial."""
    small = replace(site_config, camera=HeadCameraConfig(width_px=160, height_px=120))
    trial = TrialConfig(timeout_s=1.0, seed=4, site=small)
    config = TeleopAppConfig("live", trial, ViewConfig(port=0))
    with RemoteSite(small) as site, TeleopApp(config, site) as app:
        runner = threading.Thread(target=app.run)
        runner.start()
        try:
            assert _until(lambda: app.panel._state.value == READY)
            threading.Event().wait(0.5)
            assert app.site.time_s == 0.0  # nothing has run
            app.start_trial()
            assert _until(lambda: app.site.time_s > 0.0)
        finally:
            app.stop()
            runner.join(timeout=5.0)
        assert not runner.is_alive()


def test_a_target_under_the_table_is_not_out_of_reach(site: RemoteSite) -> None:
    """The IK holds the gripper just above the table's top: seen on the table, where it was
    pressed, it has not stopped short in the table's plane, and the page says nothing of reach."""
    rest = site.observe().gripper_m
    into = np.array([0.35, 0.10, -0.25])  # over the table's middle, 5 cm under its top
    seen = _drive(site, into, duration_s=6.0)
    gripper = site.observe().gripper_m
    assert site.config.workspace.table_top_z_m < gripper[2] < rest[2] - 0.15  # on the table
    assert np.linalg.norm(gripper[:2] - (rest + into)[:2]) < 0.01
    assert all(s.reachable for s in seen[-30:])

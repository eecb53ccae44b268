"""The operator's efference copy and its watch of the display: no oracle of the motor noise or of
what the display will show, and a lag learnt only from movements it can see."""

from __future__ import annotations

import numpy as np
import pytest

from arteleop.ar_features import MODALITIES
from arteleop.operator import (
    ArmModel,
    CalibrationPosture,
    OperatorParams,
    OperatorTraits,
    PickAndPlace,
    SyntheticOperator,
)
from arteleop.operator.minimum_jerk import minimum_jerk_profile
from arteleop.operator.simulated.hand import Hand, Submovement
from arteleop.operator.simulated.watch import DisplayWatch
from arteleop.transforms import make_transform
from tests.ar_features.frames import display_frame
from tests.operator.small_scene import BOWL_M, GRASP_M, GRASP_OFFSET_M

DOWN = np.diag([1.0, -1.0, -1.0])


def test_the_prediction_ignores_the_motor_noise_of_the_movement() -> None:
    """Two hands meant to move the same way, their noise drawn otherwise, predict alike."""
    intended = np.array([0.1, 0.0, 0.0])
    hands = []
    for noise in (np.zeros(3), np.array([0.01, -0.02, 0.005])):
        hand = Hand(np.zeros(3))
        hand.add(Submovement(0.0, intended + noise, 0.5, intended))
        for t in np.arange(0.0, 0.31, 0.01):
            hand.advance(t)
            hand.remember(t)
        hands.append(hand)
    (a, b) = hands
    assert not np.allclose(a.position_m, b.position_m)  # the hands differ...
    np.testing.assert_array_equal(a.moved_since(0.1), b.moved_since(0.1))  # ...their copies not
    np.testing.assert_array_equal(a.remaining_m(0.3), b.remaining_m(0.3))
    np.testing.assert_allclose(a.intended_m + a.remaining_m(0.3), intended)


def _shown_at(watch: DisplayWatch, t: float, gripper_m: np.ndarray) -> None:
    view = display_frame(cues=MODALITIES["embodiment"], time_s=t,
                         T_base_gripper=make_transform(DOWN, gripper_m))  # fmt: skip
    watch.see(t, view)


def _show(watch: DisplayWatch, times_s: np.ndarray, path) -> None:
    """The display at 30 Hz, its gripper at ``path(t)`` (m)."""
    for t in times_s:
        _shown_at(watch, float(t), np.asarray(path(t)))


START = np.array([0.6, -0.4, 0.0])
AWAY = np.array([0.1, 0.0, 0.0])  # the movement the operator makes: 0.1 m along x


def _moving_at(begin_s: float):
    """A display that shows the gripper still at START until ``begin_s`` (s), then going 0.2 m/s
    along x."""
    return lambda t: START + [0.2 * max(t - begin_s, 0.0), 0.0, 0.0]


FRAMES = 1 / 30


def test_the_lag_is_learnt_from_the_displays_response_half_way_and_slowly() -> None:
    """The hand is half-way at 0.25 s; the display shows the gripper half-way (50 mm along)
    from 1.05 s: the sample is the time between, and the belief takes a tenth of its difference."""
    params = OperatorParams(familiar_lag_s=0.3, lag_learning_rate=0.1)
    watch = DisplayWatch(params)
    _show(watch, np.arange(0.0, 0.2, FRAMES), _moving_at(0.8))
    watch.await_response(AWAY, visible_at_s=0.05, half_at_s=0.25)
    _show(watch, np.arange(0.2, 1.0, FRAMES), _moving_at(0.8))
    assert watch.lag_s == 0.3  # shown moving, 40 mm of 100: not half-way yet, no sample
    times = np.arange(1.0, 1.3, FRAMES)
    _show(watch, times, _moving_at(0.8))
    seen_s = times[np.argmax(0.2 * (times - 0.8) > 0.5 * AWAY[0])]  # the first frame past it
    assert watch.lag_s == pytest.approx(0.3 + 0.1 * (seen_s - 0.25 - 0.3))


def test_a_movement_too_small_to_see_teaches_no_lag() -> None:
    params = OperatorParams(motion_threshold_m=0.005, lag_learning_rate=0.5)
    watch = DisplayWatch(params)
    _show(watch, np.arange(0.0, 0.2, FRAMES), _moving_at(0.8))
    small = np.array([0.008, 0.0, 0.0])  # under two thresholds
    watch.await_response(small, visible_at_s=0.05, half_at_s=0.25)
    _show(watch, np.arange(0.2, 1.2, FRAMES), _moving_at(0.8))
    assert watch.lag_s == params.familiar_lag_s


def test_the_robots_jitter_at_rest_is_not_taken_for_the_response() -> None:
    """A gripper shaking 10 mm across the movement's way, or drifting along it slower than the
    operator's still, is not the display answering."""
    params = OperatorParams(lag_learning_rate=0.5)
    watch = DisplayWatch(params)
    _show(watch, np.arange(0.0, 0.2, FRAMES), lambda t: START)
    watch.await_response(AWAY, visible_at_s=0.05, half_at_s=0.25)
    watch.hand_stopped(0.3, wait_s=0.3)
    _show(watch, np.arange(0.2, 1.0, FRAMES),
          lambda t: START + [0.0, 0.01 * np.sin(20 * t), 0.0])  # fmt: skip
    _show(watch, np.arange(1.0, 2.0, FRAMES),
          lambda t: START + [0.5 * params.arrival_speed_m_s * (t - 1.0), 0.0, 0.0])  # fmt: skip
    # The drift, 5 mm along the way by 2 s and still by the operator's measure, would read as
    # an answered movement come to rest, were its speed not checked.
    assert not watch.arrived(2.0)
    assert watch.lag_s == params.familiar_lag_s


def test_the_operator_does_not_take_a_display_that_has_not_answered_for_one_at_rest() -> None:
    watch = DisplayWatch(OperatorParams(arrival_window_s=0.25, arrival_timeout_s=3.0))
    _show(watch, np.arange(0.0, 0.2, FRAMES), lambda t: START)
    watch.await_response(AWAY, visible_at_s=0.05, half_at_s=0.25)
    watch.hand_stopped(0.6, wait_s=0.3)
    _show(watch, np.arange(0.2, 2.0, FRAMES), lambda t: START)
    assert not watch.arrived(2.0)  # its wait is long over, but nothing has moved
    assert watch.arrived(3.7)  # it looks anyway, in the end


def test_after_its_wait_the_operator_looks_at_a_display_on_the_robots_slow_tail() -> None:
    """It does not know where the display will bring the gripper: once the display has answered,
    a gripper creeping on slower than the operator's still is taken for one at rest, and the
    operator looks at a stale frame."""
    params = OperatorParams(arrival_window_s=0.25)
    watch = DisplayWatch(params)
    _show(watch, np.arange(0.0, 0.2, FRAMES), lambda t: START)
    watch.await_response(AWAY, visible_at_s=0.05, half_at_s=0.25)
    creep = 0.5 * params.arrival_speed_m_s
    path = lambda t: START + [0.2 * np.clip(t - 0.2, 0, 0.2) + creep * max(t - 0.4, 0), 0, 0]  # noqa: E731
    watch.hand_stopped(0.5, wait_s=0.3)
    _show(watch, np.arange(0.2, 0.7, FRAMES), path)
    assert not watch.arrived(0.7)  # still waiting
    _show(watch, np.arange(0.7, 1.1, FRAMES), path)
    assert watch.arrived(1.1)  # 47 mm shown of the 100 mm made


def test_the_operator_expects_its_hand_to_end_as_it_meant_and_knows_how_unsure_that_is() -> None:
    """Half-way through a 0.1 m minimum-jerk movement of 0.5 s, against a display 0.1 s old:
    the hand goes from 0.0163 m (the profile at 0.15 s / 0.5 s) to the end, 0.0837 m; the
    belief's spread is the timing's along the way (0.15 of 0.1 s at the meant speed then) and
    the movement's scatter not yet covered then."""
    intended, sd = np.array([0.1, 0.0, 0.0]), 0.004
    hand = Hand(np.zeros(3))
    hand.add(Submovement(0.0, intended + [0.003, -0.002, 0.0], 0.5, intended, sd**2 * np.eye(3)))
    for t in np.arange(0.0, 0.2501, 0.001):
        hand.advance(t)
        hand.remember(t)
    t, lag = 0.25, 0.1
    expected, cov = hand.to_end(t, lag, timed_lag_s=lag, timing_weber=0.15)
    share = minimum_jerk_profile(np.array([(t - lag) / 0.5]))[0]
    np.testing.assert_allclose(expected, intended * (1 - share), atol=1e-6)
    speed = 0.1 / 0.5 * 30 * 0.3**2 * 0.7**2  # minimum jerk at tau = 0.3: 30 tau^2 (1 - tau)^2
    along = (0.15 * lag * speed) ** 2 + (sd * (1 - share)) ** 2
    assert cov[0, 0] == pytest.approx(along, rel=0.06)  # its speed from samples 1 ms apart
    np.testing.assert_allclose(np.diag(cov)[1:], (sd * (1 - share)) ** 2, rtol=1e-9)
    # Timing the lag shorter, it expects less of the movement still to show.
    assert hand.to_end(t, lag, timed_lag_s=0.05, timing_weber=0.15)[0][0] < expected[0]


def test_a_movement_finished_within_the_lag_is_still_unsure_on_the_display() -> None:
    """A 0.2 s movement that ended 0.05 s ago, against a display 0.1 s old: the display showed
    it at 0.15 s of its 0.2, so the share of its scatter not covered then is still to show."""
    intended, sd = np.array([0.05, 0.0, 0.0]), 0.004
    hand = Hand(np.zeros(3))
    hand.add(Submovement(0.0, intended, 0.2, intended, sd**2 * np.eye(3)))
    for t in np.arange(0.0, 0.2501, 0.01):
        hand.advance(t)
        hand.remember(t)
    assert not hand.moving
    share = minimum_jerk_profile(np.array([0.15 / 0.2]))[0]
    _, cov = hand.to_end(0.25, 0.1, timed_lag_s=0.1, timing_weber=0.15)
    np.testing.assert_allclose(np.diag(cov)[1:], (sd * (1 - share)) ** 2, rtol=1e-9)
    assert not hand.scatter_m2(0.25).any()  # nothing left now


def test_the_operators_path_holds_where_it_meant_its_hand_at_each_sample() -> None:
    """Stepped as a trial steps it, the efference copy's sample at t is the intended hand at t,
    not the step's before (which would date every prediction a sample late)."""
    task = PickAndPlace(GRASP_OFFSET_M, np.array([0.3, -0.56, 0.0]))
    rng = np.random.default_rng(3)
    op = SyntheticOperator(task, lambda p: p, ArmModel(), CalibrationPosture(), rng,
                           OperatorParams(), OperatorTraits())  # fmt: skip
    start = GRASP_M + [0.0, 0.0, 0.10]
    op.start_phase("descend", start, 0.0)
    view = display_frame(cues=MODALITIES["full"], time_s=0.0, bowl_m=BOWL_M,
                         T_base_gripper=make_transform(DOWN, start))  # fmt: skip
    moved = []
    for t in np.arange(0.0, 1.5, 0.01):
        op.step(float(t), view)
        if op.hand.moving:
            moved.append(float(np.linalg.norm(op.hand.moved_since(float(t)))))
            assert moved[-1] == 0.0
    assert len(moved) > 10  # it moved, so a late sample would have shown

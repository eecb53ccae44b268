"""The synthetic operator's decision mechanism, checked on a small scene
(tests/operator/small_scene.py); its perception is in test_perception.py."""

import re
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from numpy.typing import NDArray
from scipy.spatial.transform import Rotation, Slerp

import arteleop.operator
from arteleop.ar_features import MODALITIES, ArCues
from arteleop.errors import ConfigurationError
from arteleop.operator import (
    Expertise,
    MovementScatter,
    OperatorParams,
    OperatorTraits,
    PerceptionParams,
    SyntheticOperator,
    TraitDistribution,
    expected_time_s,
    probability_within,
    submovement_duration_s,
)
from arteleop.operator.output import ALIGN, CALIBRATE, ENGAGE
from arteleop.operator.simulated.hand import Hand, Submovement, Wrist, ramped_grip
from arteleop.operator.simulated.submovements import planned_submovement
from tests.operator.small_scene import GRASP_M, descend

# -- the decision mechanism ----------------------------------------------------------------------
SEEDS = range(16)
SCATTER = MovementScatter()


def _each(cues: ArCues, **kw) -> dict[str, NDArray[np.float64]]:
    runs = [descend(cues, seed, **kw) for seed in SEEDS]
    return {k: np.array([getattr(r, k) for r in runs])
            for k in ("duration_s", "looks", "corrections", "error_m", "overshoot_m")}  # fmt: skip


def _mean(cues: ArCues, **kw) -> dict[str, float]:
    return {k: float(v.mean()) for k, v in _each(cues, **kw).items()}


def test_a_more_precise_cue_reaches_the_criterion_sooner_and_no_less_accurately() -> None:
    """The bar's label sharpens the grasp judgement in depth: no more looks, less time, and no
    larger an error than from the cloud alone (beyond the seeds' noise: the motor noise
    dominates the error). Reading the label costs an eye movement per glance (the next test);
    here it is free, to see the precision alone (measured over 64 seeds: 2.00 against 2.03
    looks, 0.89 against 0.97 s, 7.4 against 7.7 mm)."""
    free = OperatorParams(familiar_lag_s=0.0, perception=PerceptionParams(eye_movement_s=0.0))
    plain = _each(MODALITIES["none"], params=free)
    cued = _each(MODALITIES["manipulation"], params=free)
    assert cued["looks"].mean() <= plain["looks"].mean()
    assert cued["duration_s"].mean() < 0.95 * plain["duration_s"].mean()
    worse = cued["error_m"] - plain["error_m"]
    assert worse.mean() <= 2 * worse.std(ddof=1) / np.sqrt(len(worse))


def test_a_label_to_read_costs_each_glance_an_eye_movement_and_a_beam_in_view_does_not() -> None:
    """The bar's label lies beside the gripper, outside the fovea: every glance that reads it
    moves the eyes. The beam's ends stay within the parafovea of one fixation: no eye movement
    to pay, the same descent to the bit. A strict criterion makes looks of several glances."""
    strict = OperatorTraits(grasp_criterion_scale=0.5)

    def descent(cues: ArCues, eye_movement_s: float) -> dict[str, float]:
        perception = PerceptionParams(eye_movement_s=eye_movement_s)
        params = OperatorParams(familiar_lag_s=0.0, perception=perception)
        return _mean(cues, traits=strict, params=params)

    label = MODALITIES["manipulation"]
    assert descent(label, 0.5)["duration_s"] > descent(label, 0.0)["duration_s"] + 0.3
    assert descent(ArCues(beam=True), 0.5) == descent(ArCues(beam=True), 0.0)


def test_an_arm_stopped_at_its_reach_is_met_from_the_hand_once_the_display_says_so() -> None:
    """The hand starts 25 cm beyond where the arm reaches, the grasp point 3 cm within it. A
    correction by the error the display shows moves a gripper that cannot come, so without the
    out-of-reach notice the operator ends its descent (giving up, or timed out) with its hand
    still beyond the reach; with it, it corrects from where its hand commands the gripper, and
    ends it over the grasp point. A hand 3 cm beyond the gripper is not felt apart from it
    (proprioception errs by centimetres): there the notice changes nothing."""
    reach_x_m = float(GRASP_M[0]) + 0.03
    far = {"start_beside_m": 0.28, "reach_x_m": reach_x_m, "limit_s": 15.0}
    told = [descend(ArCues(), seed, **far).error_m for seed in range(4)]
    untold = [descend(ArCues(), seed, notice=False, **far).error_m for seed in range(4)]
    assert max(told) < 0.02 < 0.1 < min(untold), (told, untold)
    near = {"start_beside_m": 0.06, "reach_x_m": reach_x_m, "limit_s": 15.0}
    assert descend(ArCues(), 0, **near) == descend(ArCues(), 0, notice=False, **near)


def test_a_stricter_criterion_costs_time_with_the_same_cue() -> None:
    strict = _mean(MODALITIES["none"], traits=OperatorTraits(grasp_criterion_scale=0.5))
    loose = _mean(MODALITIES["none"], traits=OperatorTraits(grasp_criterion_scale=1.5))
    assert strict["duration_s"] > 1.3 * loose["duration_s"]
    assert strict["error_m"] < loose["error_m"]


def test_a_lag_the_operator_has_not_practised_makes_it_overshoot_and_slows_it() -> None:
    """It acts on a view a lag old: a correction planned in flight on it overshoots. A lag it
    knows costs only the waiting (measured: 45 mm against 2 mm of overshoot)."""
    cues = MODALITIES["manipulation"]
    none = _mean(cues)
    known = _mean(cues, lag_s=0.3)  # the operator's familiar lag is the scene's
    unknown = _mean(cues, lag_s=0.3, params=OperatorParams(familiar_lag_s=0.0))
    assert unknown["overshoot_m"] > 0.03 > 3 * max(none["overshoot_m"], known["overshoot_m"])
    assert unknown["duration_s"] > known["duration_s"] > none["duration_s"]


def test_a_long_lag_the_operator_knows_makes_it_move_and_wait_without_overshoot() -> None:
    """No switch: corrections in flight wait for the last one to show, so a long lag the
    operator has learnt leaves room for few of them, and none overshoots."""
    cues = MODALITIES["manipulation"]
    short = _mean(cues, lag_s=0.3)
    waiting = _mean(cues, lag_s=0.8, params=OperatorParams(familiar_lag_s=0.8))
    assert waiting["overshoot_m"] < 0.01
    assert waiting["duration_s"] > short["duration_s"]


def test_corrections_in_flight_are_made_over_the_primarys_second_half_only(monkeypatch) -> None:
    """Online control acts in the primary's deceleration (Elliott, Helsen & Chua 2001): from
    half-way through it to its planned end; an error left after it is the next look's. Unbounded,
    an operator believing another lag than the display's chained corrections in flight: in the
    delay study's first run on this mechanism, one moved the bowl to and fro for a minute, its
    hand never stopping to look. Here the lag is unpractised, and corrections in flight many."""
    primaries: list[tuple[float, float]] = []
    in_flight: list[float] = []
    correct, home_in = SyntheticOperator._correct, SyntheticOperator._home_in

    def correct_spy(self, t, error):
        moves = len(self.hand.moves)
        correct(self, t, error)
        if len(self.hand.moves) > moves:
            primaries.append((self.hand.moves[-1].start_s, self.hand.moves[-1].duration_s))

    def home_in_spy(self, t, view):
        made = self.corrections_total
        home_in(self, t, view)
        if self.corrections_total > made:
            in_flight.append(t)

    monkeypatch.setattr(SyntheticOperator, "_correct", correct_spy)
    monkeypatch.setattr(SyntheticOperator, "_home_in", home_in_spy)
    unpractised = OperatorParams(familiar_lag_s=0.0)
    for seed in range(4):
        primaries.clear()
        in_flight.clear()
        descend(MODALITIES["manipulation"], seed, lag_s=0.3, params=unpractised,
                start_above_m=0.35)  # fmt: skip
        assert len(in_flight) >= 3
        for t in in_flight:
            start_s, duration_s = max(p for p in primaries if p[0] <= t)
            assert start_s + duration_s / 2 <= t < start_s + duration_s


def test_a_participants_traits_last_across_their_trials_and_differ_between_people() -> None:
    from arteleop.study import StudyConfig
    from arteleop.study.cohort import participants
    from arteleop.study.protocol import operator_traits

    study = StudyConfig()
    people = participants(study)
    first = [operator_traits(study, person) for person in people]
    assert first == [operator_traits(study, person) for person in people]  # every trial alike
    assert len({t.confidence for t in first}) == len(people)
    assert len({t.bias_seed for t in first}) == len(people)
    other_study = [operator_traits(replace(study, seed=1), person) for person in people]
    assert first != other_study
    d = TraitDistribution()
    expert = d.draw(0, "P01", Expertise(avr_hours=2, games_hours=3))
    novice = d.draw(0, "P01", Expertise())
    assert expert.depth_factor == d.avr_depth_factor and novice.depth_factor == 1.0
    assert expert.movement_time_factor == pytest.approx(d.games_speed_factor)
    assert expert.confidence == novice.confidence  # expertise does not touch the criterion


def test_no_modality_name_appears_in_the_operators_decision_code() -> None:
    """Cues differ only in what the display frame shows: the operator reads its layers' flags,
    never which modality a trial runs under."""
    folder = Path(arteleop.operator.__file__).parent / "simulated"
    names = "|".join(MODALITIES)
    for module in ("synthetic", "hand", "watch", "params", "perception", "belief",
                   "submovements", "traits", "tasks/task", "tasks/pick_and_place",
                   "tasks/pointing"):  # fmt: skip
        code = (folder / f"{module}.py").read_text()
        assert not re.search(rf"[\"']({names})[\"']", code), module
        assert not re.search(r"modalit|MODALITIES|modality_cues", code, re.IGNORECASE), module


def test_the_belief_is_a_gaussian_against_the_criterion() -> None:
    """Isotropic errors: the chi distribution with 3 (or, in the plane, 2) degrees of freedom."""
    from scipy.stats import chi

    sd = 0.01
    for c in (0.005, 0.01, 0.02, 0.03):
        p3 = probability_within(np.zeros(3), np.eye(3) * sd**2, c)
        p2 = probability_within(np.array([0, 0, 0.5]), np.eye(3) * sd**2, c, "xy")
        assert p3 == pytest.approx(chi.cdf(c / sd, 3), abs=0.01)
        assert p2 == pytest.approx(chi.cdf(c / sd, 2), abs=0.01)
    assert probability_within(np.array([0.02, 0, 0]), np.zeros((3, 3)), 0.019) == 0.0


def test_the_scatter_is_guiard_and_riouls_fit_where_its_data_are_and_schmidts_law_faster() -> None:
    """Within the fit's movement times its equation holds; faster, the scatter at a given
    amplitude grows as the mean speed; the two meet where the data begin."""
    law = SCATTER
    for x in (0.69, 0.96, 1.45, 2.06):
        y = float(law.along_share(x))
        lhs = (y - law.y0) ** (1 - law.alpha) * (x - law.x0_s) ** law.alpha
        assert lhs == pytest.approx(law.k**law.alpha, rel=1e-9)
    edge = float(law.along_share(law.fit_from_s))
    for x in (0.1, 0.3, 0.5):
        assert float(law.along_share(x)) == pytest.approx(edge * law.fit_from_s / x, rel=1e-12)
    # 15 cm at the fastest instruction: about what people's endpoints showed (8.6 mm), at
    # least their order; at the slowest 1.3 mm (0.3 mm with their corrections).
    assert 0.15 * edge == pytest.approx(0.0063, abs=0.0002)


def test_the_scatter_grows_with_speed_along_the_movement_and_not_across() -> None:
    """Drawn endpoints of a 30 cm movement along x at three durations: the SD along grows as
    the movement gets faster, the SD across stays the angle's; the ellipse lies along the way
    for fast movements."""
    rng = np.random.default_rng(5)
    delta = np.array([0.3, 0.0, 0.0])
    sds = {}
    for duration in (0.4, 0.8, 1.6):
        draws = np.array([SCATTER.endpoint_error_m(delta, duration, rng) for _ in range(4000)])
        sds[duration] = draws.std(axis=0)
        np.testing.assert_allclose(
            np.cov(draws.T), SCATTER.covariance_m2(delta, duration), atol=5e-6, rtol=0.08
        )
    along = [sds[d][0] for d in (1.6, 0.8, 0.4)]
    across = [sds[d][1] for d in (1.6, 0.8, 0.4)]
    assert along[0] < along[1] < along[2]
    assert along[2] / along[0] > 3.0
    assert max(across) / min(across) < 1.1
    assert along[2] > 2 * across[2]
    assert across[0] == pytest.approx(0.3 * SCATTER.direction_sd_rad, rel=0.05)


def test_a_movements_duration_rises_with_its_amplitude_at_a_persons_speed() -> None:
    """Planned in full (the arm's speed a cap, the person's own factor), a longer movement to
    the same tolerance takes longer."""
    rng = np.random.default_rng(0)
    params = OperatorParams()
    durations = [
        planned_submovement(np.array([a, 0.0, 0.0]), 0.0, 0.01, 1.0, params, 1.0, rng).duration_s
        for a in (0.02, 0.05, 0.1, 0.2, 0.4)
    ]
    assert np.all(np.diff(durations) > 0), durations


def test_fitts_law_comes_out_of_the_planner_and_a_costly_look_slows_the_movement() -> None:
    rows = []
    for a in (0.1, 0.2, 0.4):
        for w in (0.01, 0.02, 0.04):
            rows.append((np.log2(a / w + 1), expected_time_s(a, w / 2, 0.6, SCATTER)))
    ids, times = np.array(rows).T
    slope, _ = np.polyfit(ids, times, 1)
    assert slope > 0.1 and np.corrcoef(ids, times)[0, 1] ** 2 > 0.9
    cheap = submovement_duration_s(0.2, 0.01, 0.3, SCATTER)
    costly = submovement_duration_s(0.2, 0.01, 1.5, SCATTER)
    assert costly > cheap


@pytest.mark.parametrize(
    ("look_cost_s", "scatter"),
    [(0.3, SCATTER), (0.6, SCATTER), (1.5, MovementScatter(direction_sd_rad=0.0))],
)
def test_submovement_policy_is_the_plain_dynamic_programme_to_the_bit(
    look_cost_s: float, scatter: MovementScatter
) -> None:
    """The planner keeps what does not change across its iterations; its table must equal the
    programme written out plainly (the module docstring's formula, durations rising with the
    amplitude over criterion), value for value."""
    from arteleop.operator.simulated.submovements import (
        _ACROSS_Q,
        _ALONG_Q,
        _D,
        _X,
        _policy,
        _rising_argmin,
    )

    durations = _D[None, :]
    value = np.zeros_like(_X)
    y = scatter.along_share(_D)[None, :, None]
    r = np.sqrt(y**2 * _ALONG_Q + scatter.direction_sd_rad**2 * _ACROSS_Q)
    for _ in range(60):
        left = _X[:, None, None] * r
        future = np.interp(np.log(np.maximum(left, _X[0])), np.log(_X), value)
        expected = np.where(left <= 1.0, 0.0, future).mean(axis=2)
        total = durations + look_cost_s + expected
        choice = _rising_argmin(total)
        new, best = total[np.arange(len(_X)), choice], _D[choice]
        if np.max(np.abs(new - value)) < 1e-6:
            break
        value = new
    kept_value, kept_best = _policy.__wrapped__(look_cost_s, scatter)
    np.testing.assert_array_equal(kept_value, value)
    np.testing.assert_array_equal(kept_best, best)
    assert len(np.unique(best)) > 5, "premise: the durations vary with the distance"


def test_the_rising_choice_is_the_cheapest_of_all_rising_ones() -> None:
    """Against every rising path through a small table of costs, enumerated."""
    import itertools

    from arteleop.operator.simulated.submovements import _rising_argmin

    rng = np.random.default_rng(42)
    for _ in range(20):
        total = rng.uniform(0.0, 1.0, (4, 5))
        paths = [p for p in itertools.product(range(5), repeat=4) if list(p) == sorted(p)]
        cheapest = min(paths, key=lambda p: sum(total[i, j] for i, j in enumerate(p)))
        choice = _rising_argmin(total)
        assert list(np.diff(choice) >= 0) == [True] * 3
        assert total[np.arange(4), choice].sum() == pytest.approx(
            sum(total[i, j] for i, j in enumerate(cheapest))
        )


@pytest.mark.parametrize("look_cost_s", [0.3, 0.6, 1.0, 2.0])
def test_a_longer_movement_or_a_smaller_tolerance_is_never_planned_faster(
    look_cost_s: float,
) -> None:
    amplitudes = np.geomspace(0.005, 0.6, 200)
    for criterion in (0.0025, 0.005, 0.01, 0.02):
        durations = [submovement_duration_s(a, criterion, look_cost_s, SCATTER) for a in amplitudes]
        assert np.all(np.diff(durations) >= 0), (look_cost_s, criterion)
    narrow = [submovement_duration_s(0.3, c, look_cost_s, SCATTER) for c in (0.02, 0.01, 0.005)]
    assert np.all(np.diff(narrow) >= 0)


@pytest.mark.parametrize(
    ("build", "message"),
    [
        (lambda: OperatorTraits(confidence=1.2),
         "OperatorTraits.confidence = 1.2: expected 0.5-0.999 (a probability)."),
        (lambda: OperatorTraits(placement_criterion_m=0.0),
         "OperatorTraits.placement_criterion_m = 0.0: expected 0.001-0.1 (m)."),
        (lambda: OperatorParams(peak_speed_m_s=-1.0),
         "OperatorParams.peak_speed_m_s = -1.0: expected > 0."),
        (lambda: MovementScatter(direction_sd_rad=1.0),
         "MovementScatter.direction_sd_rad = 1.0: expected 0-0.5 (rad)."),
        (lambda: MovementScatter(x0_s=0.8),
         "MovementScatter.fit_from_s = 0.69: expected > 0.8 and <= 10.0 (s)."),
        (lambda: OperatorParams(familiar_lag_s=float("nan")),
         "OperatorParams.familiar_lag_s = nan: expected >= 0."),
        (lambda: OperatorParams(timing_weber=2.0),
         "OperatorParams.timing_weber = 2.0: expected 0-1 (a share of the wait)."),
        (lambda: OperatorParams(lag_learning_rate=-0.1),
         "OperatorParams.lag_learning_rate = -0.1: expected 0-1 (a share)."),
        (lambda: OperatorParams(motion_threshold_m=0.0),
         "OperatorParams.motion_threshold_m = 0.0: expected > 0."),
    ],
)  # fmt: skip
def test_an_operator_constant_out_of_range_is_refused_by_name(build, message: str) -> None:
    with pytest.raises(ConfigurationError) as err:
        build()
    assert str(err.value) == message


def test_the_grip_ramps_over_its_wait_and_the_wrist_turns_as_the_hand_aligns() -> None:
    # Squeezing from 0.2 over the 0.4 s that end at 3 s: a quarter of the way at 2.7 s.
    assert ramped_grip(0.2, 1.0, 2.7, 3.0, 0.4) == pytest.approx(0.4)
    assert ramped_grip(0.2, 1.0, 3.5, 3.0, 0.4) == 1.0
    assert ramped_grip(1.0, 0.0, 2.8, 3.0, 0.4) == pytest.approx(0.5)
    start, work = Rotation.identity(), Rotation.from_euler("y", 0.3)
    wrist = Wrist(Slerp([0.0, 1.0], Rotation.concatenate([start, work])), 0.3)
    hand = Hand(np.zeros(3))
    hand.add(Submovement(1.0, np.array([0.1, 0.0, 0.0]), 2.0, np.array([0.1, 0.0, 0.0])))
    np.testing.assert_allclose(wrist.rotation(CALIBRATE, hand, 2.0), np.eye(3), atol=1e-12)
    # Half-way through the alignment's minimum-jerk movement, half-way round.
    half = Rotation.from_euler("y", 0.15).as_matrix()
    np.testing.assert_allclose(wrist.rotation(ALIGN, hand, 2.0), half, atol=1e-12)
    np.testing.assert_allclose(wrist.rotation(ENGAGE, hand, 2.0), work.as_matrix(), atol=1e-12)

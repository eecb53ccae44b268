"""The synthetic operator's perception, checked statistically, and its decision mechanism,
checked on a small scene (tests/operator/small_scene.py)."""

import re
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

import arteleop.operator
from arteleop.ar_features import MODALITIES, ArCues, DisplayFrame
from arteleop.errors import ConfigurationError
from arteleop.operator import (
    Expertise,
    OperatorParams,
    OperatorTraits,
    TraitDistribution,
    expected_time_s,
    probability_within,
    submovement_duration_s,
)
from arteleop.operator.perception import (
    BowlMemory,
    Perceived,
    PerceptionParams,
    PerceptualErrors,
    perceive,
)
from tests.ar_features.frames import display_frame
from tests.operator.small_scene import descend

P = PerceptionParams()


class _Independent(PerceptualErrors):
    """Every glance a look of its own and no bias, to sample one glance's spread."""

    def __init__(self, seed: int) -> None:
        super().__init__(np.random.default_rng(seed), bias_seed=0, bias_share=0.0)

    def draw(self, stream: str, size: int) -> np.ndarray:
        self.new_look()
        return super().draw(stream, size)


def _independent(seed: int) -> PerceptualErrors:
    return _Independent(seed)


def _view(cues: ArCues, gripper_in_camera: bool = True) -> DisplayFrame:
    return display_frame(cues=cues, gripper_in_camera=gripper_in_camera)


def _errors(cues: ArCues, n: int = 4000, **kw) -> dict[str, np.ndarray]:
    noise = _independent(0)
    view = _view(cues, **kw)
    seen = [perceive(view, P, noise) for _ in range(n)]
    return {
        "relative": np.array(
            [(s.gripper_m - s.bowl_m) - (view.gripper_m - view.bowl_m) for s in seen]
        ),
        "target_vs_bowl": np.array(
            [(s.target_m - s.bowl_m)[:2] - (view.target_m - view.bowl_m)[:2] for s in seen]
        ),
    }


def test_distance_bar_and_beam_sharpen_the_gripper_to_grasp_judgement() -> None:
    plain = np.linalg.norm(_errors(MODALITIES["none"])["relative"], axis=1)
    cued = np.linalg.norm(_errors(MODALITIES["manipulation"])["relative"], axis=1)
    # Depth dominates without cues (15 mm); bar and beam bring it to a few millimetres.
    assert np.sqrt(np.mean(plain**2)) == pytest.approx(
        np.sqrt(P.depth_sd_m**2 + 2 * P.lateral_sd_m**2), rel=0.05
    )
    assert np.sqrt(np.mean(cued**2)) == pytest.approx(
        np.sqrt(P.bar_sd_m**2 + 2 * P.beam_sd_m**2), rel=0.05
    )


def test_target_mesh_turns_placement_into_a_coincidence_judgement() -> None:
    without = _errors(MODALITIES["none"])["target_vs_bowl"].std(axis=0)
    with_mesh = _errors(MODALITIES["task"])["target_vs_bowl"].std(axis=0)
    np.testing.assert_allclose(with_mesh, P.target_mesh_sd_m, rtol=0.05)
    assert np.all(without > 2.5 * with_mesh)


def test_ghost_shows_a_gripper_the_camera_cannot() -> None:
    noise = _independent(1)
    hidden = [
        perceive(_view(MODALITIES["none"], gripper_in_camera=False), P, noise) for _ in range(3000)
    ]
    ghost = [
        perceive(_view(MODALITIES["embodiment"], gripper_in_camera=False), P, noise)
        for _ in range(3000)
    ]
    assert not hidden[0].gripper_seen and ghost[0].gripper_seen
    err_hidden = np.std([s.gripper_m - _view(ArCues()).gripper_m for s in hidden], axis=0)
    np.testing.assert_allclose(err_hidden, P.proprioception_sd_m, rtol=0.1)  # from one's own arm
    assert not hidden[0].closure_known and ghost[0].closure_known


def test_a_bowl_the_display_does_not_show_is_not_perceived() -> None:
    noise = _independent(2)
    view = display_frame(cues=MODALITIES["full"], bowl_m=None)
    seen = [perceive(view, P, noise) for _ in range(4000)]
    assert all(s.bowl_m is None for s in seen)
    # No bar or beam value without a tracked bowl: the gripper is judged from the cloud alone.
    err = np.array([s.gripper_m - view.gripper_m for s in seen])
    assert np.sqrt(np.mean(np.sum(err**2, axis=1))) == pytest.approx(
        np.sqrt(P.depth_sd_m**2 + 2 * P.lateral_sd_m**2), rel=0.05
    )


def test_the_operator_remembers_a_hidden_bowl_and_carries_it_with_the_hand() -> None:
    def look(gripper: list[float], bowl: list[float] | None) -> Perceived:
        return Perceived(
            np.array(gripper),
            None if bowl is None else np.array(bowl),
            np.zeros(3),
            True,
            True,
            np.eye(3) * 1e-4,
            np.eye(3) * 1e-4,
            False,
        )

    memory = BowlMemory()
    assert memory.bowl_m(look([0.0, 0.0, 0.1], None)) is None  # never seen
    shown = look([0.5, -0.3, 0.0], [0.6, -0.4, -0.2])
    np.testing.assert_array_equal(memory.bowl_m(shown), [0.6, -0.4, -0.2])
    # Hidden by the arm: where it was last seen.
    np.testing.assert_array_equal(memory.bowl_m(look([0.9, 0.9, 0.9], None)), [0.6, -0.4, -0.2])
    memory.grasp(shown, shown.bowl_m)
    carried = memory.bowl_m(look([0.7, 0.0, 0.1], None))
    np.testing.assert_allclose(carried, [0.8, -0.1, -0.1])  # moved with the gripper
    assert not memory.left_behind(look([0.7, 0.0, 0.1], [0.8, -0.1, -0.1]))
    assert memory.left_behind(look([0.7, 0.0, 0.1], [0.6, -0.4, -0.2]))  # the grasp missed
    memory.release()
    np.testing.assert_array_equal(memory.bowl_m(look([0.7, 0.0, 0.1], None)), [0.6, -0.4, -0.2])


def test_a_carried_bowl_is_judged_within_its_own_frame_under_the_predictive_ghost() -> None:
    """The predictive ghost's gripper is 15 cm up (lifting) while the delayed frame still shows
    the arm, and the bowl in its hand, at the table: the bowl was not left behind, and it is
    believed where the lifting hand carries it."""
    memory = BowlMemory()
    at_grasp = Perceived(
        np.array([0.5, -0.3, 0.0]), np.array([0.6, -0.4, -0.2]), np.zeros(3), True, True,
        np.eye(3) * 1e-4, np.eye(3) * 1e-4, False,
    )  # fmt: skip
    memory.grasp(at_grasp, at_grasp.bowl_m)
    lifting = replace(
        at_grasp, gripper_m=np.array([0.5, -0.3, 0.15]), lead_m=np.array([0, 0, 0.15])
    )
    assert not memory.left_behind(lifting)
    np.testing.assert_allclose(memory.bowl_m(lifting), [0.6, -0.4, -0.05])
    # Had the grasp missed, the frame's own arm rises while the bowl stays: left behind.
    missed = replace(lifting, lead_m=np.zeros(3))
    assert memory.left_behind(missed)


def test_the_bar_and_beam_are_read_along_the_drawn_beam() -> None:
    view = _view(MODALITIES["manipulation"])
    beam = view.gripper_m - view.grasp_point_m()  # the layers' own grasp point
    beam /= np.linalg.norm(beam)
    relative = _errors(MODALITIES["manipulation"])["relative"]
    along = relative @ beam
    across = relative - np.outer(along, beam)
    assert along.std() == pytest.approx(P.bar_sd_m, rel=0.05)  # the bar: the distance
    assert np.sqrt((across**2).sum(axis=1).mean() / 2) == pytest.approx(P.beam_sd_m, rel=0.05)


def test_a_judgement_keeps_its_bias_and_a_longer_look_averages_the_rest() -> None:
    """Each stream is bias + fresh noise, variance split by ``bias_share``; n glances keep the
    bias and divide the fresh variance by n, and a new trial of the same person errs with the
    same bias."""
    streams = [f"s{i}" for i in range(6000)]
    person = PerceptualErrors(np.random.default_rng(3), bias_seed=11, bias_share=0.5)
    one = np.array([person.draw(s, 1)[0] for s in streams])  # one glance each
    assert one.std() == pytest.approx(1.0, abs=0.03)
    for _ in range(8):
        nine = np.array([person.draw(s, 1)[0] for s in streams])  # up to nine glances
    assert nine.var() == pytest.approx(0.5 + 0.5 / 9, abs=0.03)
    assert P.belief_scale(9) == pytest.approx(0.5 + 0.5 / 9)
    next_trial = PerceptualErrors(np.random.default_rng(99), bias_seed=11, bias_share=1.0)
    bias = np.array([next_trial.draw(s, 1)[0] for s in streams])
    other = PerceptualErrors(np.random.default_rng(99), bias_seed=12, bias_share=1.0)
    other_bias = np.array([other.draw(s, 1)[0] for s in streams])
    # The same person's bias in any trial: what the averaged looks converge on.
    assert np.corrcoef(nine, bias)[0, 1] == pytest.approx(np.sqrt(0.5 / (0.5 + 0.5 / 9)), abs=0.03)
    assert abs(np.corrcoef(bias, other_bias)[0, 1]) < 0.05


def test_the_mesh_guides_the_gripper_while_the_arm_hides_the_bowl() -> None:
    """With the bowl in hand hidden, the mesh is judged against the gripper beside it: the
    target relative to the gripper errs by the mesh's SD; without the mesh, by two points'."""
    noise = _independent(4)
    hidden = {"bowl_m": None, "gripper_in_camera": True}
    for cues, sd in (
        (MODALITIES["task"], P.target_mesh_sd_m),
        (MODALITIES["none"], None),
    ):
        view = display_frame(cues=cues, **hidden)
        seen = [perceive(view, P, noise) for _ in range(4000)]
        relative = np.array(
            [(s.target_m - s.gripper_m)[:2] - (view.target_m - view.gripper_m)[:2] for s in seen]
        )
        if sd is not None:
            np.testing.assert_allclose(relative.std(axis=0), sd, rtol=0.06)
            np.testing.assert_allclose(np.diag(seen[0].placement_cov)[:2], sd**2)
        else:
            assert np.all(relative.std(axis=0) > 3 * P.target_mesh_sd_m)
            assert np.all(np.diag(seen[0].placement_cov)[:2] > 9 * P.target_mesh_sd_m**2)
        assert seen[0].placed_by_gripper  # the bowl's place in the hand adds its uncertainty


@pytest.mark.parametrize(
    ("modality", "misled_grasp", "misled_place"),
    [("none", False, False), ("embodiment", True, False), ("manipulation", True, False),
     ("task", False, True), ("full", True, True)],
)  # fmt: skip
def test_a_misregistered_cloud_misleads_only_the_ar_layers(
    modality: str, misled_grasp: bool, misled_place: bool
) -> None:
    """The cloud, shifted by s, shows the real gripper, the bowl and the marker shifted alike:
    judged against each other, the shift cancels. The ghost, the beam and the target mesh stay
    where the robot and the task put them: against the shifted bowl they are off by s. Without
    perceptual noise the judgements are exact, so the errors are s or 0 to the bit."""
    s = np.array([0.03, -0.02, 0.0])
    shift = np.eye(4)
    shift[:3, 3] = s
    true_bowl = np.array([0.68, -0.45, -0.2])
    view = display_frame(cues=MODALITIES[modality], bowl_m=true_bowl + s, T_cloud_true=shift)
    exact = replace(P, depth_sd_m=0.0, lateral_sd_m=0.0, bar_sd_m=0.0, beam_sd_m=0.0,
                    centring_fraction=0.0, target_mesh_sd_m=0.0)  # fmt: skip
    seen = perceive(view, exact, _independent(1))
    grasp_error = (seen.gripper_m - seen.bowl_m) - (view.gripper_m - true_bowl)
    place_error = (seen.target_m - seen.bowl_m) - (view.target_m - true_bowl)
    np.testing.assert_allclose(grasp_error, -s if misled_grasp else 0.0, atol=1e-15)
    np.testing.assert_allclose(place_error, -s if misled_place else 0.0, atol=1e-15)


# -- the decision mechanism ----------------------------------------------------------------------
SEEDS = range(16)


def _mean(cues: ArCues, **kw) -> dict[str, float]:
    runs = [descend(cues, seed, **kw) for seed in SEEDS]
    return {k: float(np.mean([getattr(r, k) for r in runs]))
            for k in ("duration_s", "looks", "corrections", "error_m", "overshoot_m")}  # fmt: skip


def test_a_more_precise_cue_reaches_the_criterion_sooner_and_no_less_accurately() -> None:
    """The bar and the beam sharpen the grasp judgement: no more looks, less time, and a smaller
    error than from the cloud alone (measured: 2.0 against 2.2 looks, 0.68 against 1.24 s,
    8.6 against 12.9 mm)."""
    plain, cued = _mean(MODALITIES["none"]), _mean(MODALITIES["manipulation"])
    assert cued["looks"] <= plain["looks"]
    assert cued["duration_s"] < 0.8 * plain["duration_s"]
    assert cued["error_m"] < 0.8 * plain["error_m"]


def test_a_stricter_criterion_costs_time_with_the_same_cue() -> None:
    strict = _mean(MODALITIES["none"], traits=OperatorTraits(grasp_criterion_scale=0.5))
    loose = _mean(MODALITIES["none"], traits=OperatorTraits(grasp_criterion_scale=1.5))
    assert strict["duration_s"] > 1.3 * loose["duration_s"]
    assert strict["error_m"] < loose["error_m"]


def test_a_lag_the_operator_has_not_practised_makes_it_overshoot_and_slows_it() -> None:
    """It acts on a view a lag old: a correction planned in flight on it overshoots. A lag it
    knows costs only the waiting (measured: 12 cm against 3 mm of overshoot)."""
    cues = MODALITIES["manipulation"]
    none = _mean(cues)
    known = _mean(cues, lag_s=0.3)  # the operator's familiar lag is the scene's
    unknown = _mean(cues, lag_s=0.3, params=OperatorParams(familiar_lag_s=0.0))
    assert unknown["overshoot_m"] > 0.05 > 3 * max(none["overshoot_m"], known["overshoot_m"])
    assert unknown["duration_s"] > known["duration_s"] > none["duration_s"]


def test_a_long_lag_the_operator_knows_makes_it_move_and_wait_without_overshoot() -> None:
    """No switch: corrections in flight wait for the last one to show, so a long lag the
    operator has learnt leaves room for few of them, and none overshoots."""
    cues = MODALITIES["manipulation"]
    short = _mean(cues, lag_s=0.3)
    waiting = _mean(cues, lag_s=0.8, params=OperatorParams(familiar_lag_s=0.8))
    assert waiting["overshoot_m"] < 0.01
    assert waiting["duration_s"] > short["duration_s"]


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
    folder = Path(arteleop.operator.__file__).parent
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


def test_fitts_law_comes_out_of_the_planner_and_a_costly_look_slows_the_movement() -> None:
    rows = []
    for a in (0.1, 0.2, 0.4):
        for w in (0.01, 0.02, 0.04):
            rows.append((np.log2(a / w + 1), expected_time_s(a, w / 2, 0.6, 0.012)))
    ids, times = np.array(rows).T
    slope, _ = np.polyfit(ids, times, 1)
    assert slope > 0.1 and np.corrcoef(ids, times)[0, 1] ** 2 > 0.9
    cheap = submovement_duration_s(0.2, 0.01, 0.3, 0.012)
    costly = submovement_duration_s(0.2, 0.01, 1.5, 0.012)
    assert costly > cheap


@pytest.mark.parametrize(("look_cost_s", "noise_k_s"), [(0.3, 0.012), (0.6, 0.012), (1.5, 0.03)])
def test_submovement_policy_is_the_plain_dynamic_programme_to_the_bit(
    look_cost_s: float, noise_k_s: float
) -> None:
    """The planner keeps what does not change across its iterations; its table must equal the
    programme written out plainly (the module docstring's formula, durations rising with the
    amplitude over criterion), value for value."""
    from arteleop.operator.submovements import _D, _Q, _X, _policy, _rising_argmin

    durations = _D[None, :]
    value = np.zeros_like(_X)
    for _ in range(60):
        left = (_X[:, None, None] * noise_k_s / durations[:, :, None]) * _Q[None, None, :]
        future = np.interp(np.log(np.maximum(left, _X[0])), np.log(_X), value)
        expected = np.where(left <= 1.0, 0.0, future).mean(axis=2)
        total = durations + look_cost_s + expected
        choice = _rising_argmin(total)
        new, best = total[np.arange(len(_X)), choice], _D[choice]
        if np.max(np.abs(new - value)) < 1e-6:
            break
        value = new
    kept_value, kept_best = _policy.__wrapped__(look_cost_s, noise_k_s)
    np.testing.assert_array_equal(kept_value, value)
    np.testing.assert_array_equal(kept_best, best)
    assert len(np.unique(best)) > 5, "premise: the durations vary with the distance"


def test_the_rising_choice_is_the_cheapest_of_all_rising_ones() -> None:
    """Against every rising path through a small table of costs, enumerated."""
    import itertools

    from arteleop.operator.submovements import _rising_argmin

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
        durations = [submovement_duration_s(a, criterion, look_cost_s, 0.012) for a in amplitudes]
        assert np.all(np.diff(durations) >= 0), (look_cost_s, criterion)
    narrow = [submovement_duration_s(0.3, c, look_cost_s, 0.012) for c in (0.02, 0.01, 0.005)]
    assert np.all(np.diff(narrow) >= 0)


@pytest.mark.parametrize(
    ("build", "message"),
    [
        (lambda: OperatorTraits(confidence=1.2),
         "OperatorTraits.confidence = 1.2: expected 0.5-0.999 (a probability)."),
        (lambda: OperatorTraits(placement_criterion_m=0.0),
         "OperatorTraits.placement_criterion_m = 0.0: expected 0.001-0.1 (m)."),
        (lambda: OperatorParams(noise_k_s=-1.0), "OperatorParams.noise_k_s = -1.0: expected > 0."),
        (lambda: OperatorParams(familiar_lag_s=float("nan")),
         "OperatorParams.familiar_lag_s = nan: expected >= 0."),
        (lambda: OperatorParams(timing_weber=2.0),
         "OperatorParams.timing_weber = 2.0: expected 0-1 (a share of the wait)."),
        (lambda: OperatorParams(lag_learning_rate=-0.1),
         "OperatorParams.lag_learning_rate = -0.1: expected 0-1 (a share)."),
        (lambda: OperatorParams(motion_threshold_m=0.0),
         "OperatorParams.motion_threshold_m = 0.0: expected > 0."),
        (lambda: PerceptionParams(bias_share=2.0),
         "PerceptionParams.bias_share = 2.0: expected 0-1."),
    ],
)  # fmt: skip
def test_an_operator_constant_out_of_range_is_refused_by_name(build, message: str) -> None:
    with pytest.raises(ConfigurationError) as err:
        build()
    assert str(err.value) == message

"""The synthetic operator's perception and expertise, checked statistically."""

from dataclasses import replace

import numpy as np
import pytest

from arteleop.ar_features import MODALITIES, ArCues, DisplayFrame
from arteleop.operator import ArmModel, CalibrationPosture
from arteleop.operator.perception import (
    BowlMemory,
    Perceived,
    PerceptionParams,
    PerceptualNoise,
    perceive,
)
from arteleop.operator.synthetic import Expertise, Phase, SyntheticOperator, TaskGeometry
from tests.ar_features.frames import display_frame

P = PerceptionParams()


def _independent(seed: int) -> PerceptualNoise:
    """Every look independent of the last (no persistence), to sample the errors' spread."""
    return PerceptualNoise(np.random.default_rng(seed), persistence_s=0.0)


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


def test_expertise_speeds_up_and_steadies_the_operator() -> None:
    task = TaskGeometry(np.zeros(3), np.array([0.3, -0.56, 0.0]))

    def make(e: Expertise) -> SyntheticOperator:
        rng = np.random.default_rng(0)
        return SyntheticOperator(
            task, lambda p: p, ArmModel(), CalibrationPosture(), rng, expertise=e
        )

    novice, expert = make(Expertise(1, 1)), make(Expertise(avr_hours=2))
    assert expert._fitts_s(0.3, 0.01) < novice._fitts_s(0.3, 0.01)
    assert novice._fitts_s(0.3, 0.01) == pytest.approx(
        0.3 + 0.3 * np.log2(31)
    )  # Fitts, Shannon form
    assert expert._noise < novice._noise


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
            0.01,
            0.01,
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


def test_the_bar_and_beam_are_read_along_the_drawn_beam() -> None:
    view = _view(MODALITIES["manipulation"])
    beam = view.gripper_m - view.grasp_point_m()  # the layers' own grasp point
    beam /= np.linalg.norm(beam)
    relative = _errors(MODALITIES["manipulation"])["relative"]
    along = relative @ beam
    across = relative - np.outer(along, beam)
    assert along.std() == pytest.approx(P.bar_sd_m, rel=0.05)  # the bar: the distance
    assert np.sqrt((across**2).sum(axis=1).mean() / 2) == pytest.approx(P.beam_sd_m, rel=0.05)


def test_perceptual_errors_persist_with_the_stated_correlation_time() -> None:
    noise = PerceptualNoise(np.random.default_rng(3), persistence_s=10.0)
    streams = [f"s{i}" for i in range(6000)]
    first = np.array([noise.draw(s, 0.0, 1)[0] for s in streams])
    again = np.array([noise.draw(s, 0.0, 1)[0] for s in streams])
    later = np.array([noise.draw(s, 5.0, 1)[0] for s in streams])
    np.testing.assert_array_equal(again, first)  # the same frame, the same judgement
    assert later.std() == pytest.approx(1.0, abs=0.03)  # each look keeps the stated SD
    assert np.corrcoef(first, later)[0, 1] == pytest.approx(np.exp(-0.5), abs=0.03)


def test_persistent_errors_do_not_average_out_over_looks() -> None:
    """Looking again a second later gives nearly the same misjudgement: the mean of ten looks
    errs almost as much as one look (independent looks would err sqrt(10) times less)."""
    view = _view(MODALITIES["none"])
    means = []
    for seed in range(400):
        noise = PerceptualNoise(np.random.default_rng(seed), P.persistence_s)
        looks = [perceive(replace(view, time_s=t), P, noise).bowl_m for t in range(10)]
        means.append(np.mean(looks, axis=0) - view.bowl_m)
    rms = np.sqrt(np.mean(np.sum(np.array(means) ** 2, axis=1)))
    one_look = np.sqrt(P.depth_sd_m**2 + 2 * P.lateral_sd_m**2)
    assert 0.8 * one_look < rms < one_look


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
            assert seen[0].placement_sd_m == pytest.approx(np.sqrt(2) * sd)
        else:
            assert np.all(relative.std(axis=0) > 3 * P.target_mesh_sd_m)
            assert seen[0].placement_sd_m > 5 * np.sqrt(2) * P.target_mesh_sd_m


def test_the_operator_does_not_correct_an_error_it_cannot_see() -> None:
    task = TaskGeometry(np.zeros(3), np.array([0.3, -0.56, 0.0]))
    operator = SyntheticOperator(
        task, lambda p: p, ArmModel(), CalibrationPosture(), np.random.default_rng(0)
    )
    seen = Perceived(np.zeros(3), np.zeros(3), np.zeros(3), True, True, 0.004, 0.02)
    operator.phase = Phase.DESCEND
    assert operator._discernible_m(seen) == pytest.approx(0.004)
    operator.phase = Phase.LOWER
    assert operator._discernible_m(seen) == pytest.approx(0.02)
    operator.phase = Phase.LIFT  # moving the hand, not judging a scene
    assert operator._discernible_m(seen) == 0.0


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
    seen = perceive(view, P, _independent(1), noise_scale=0.0)
    grasp_error = (seen.gripper_m - seen.bowl_m) - (view.gripper_m - true_bowl)
    place_error = (seen.target_m - seen.bowl_m) - (view.target_m - true_bowl)
    np.testing.assert_allclose(grasp_error, -s if misled_grasp else 0.0, atol=1e-15)
    np.testing.assert_allclose(place_error, -s if misled_place else 0.0, atol=1e-15)

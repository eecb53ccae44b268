"""The synthetic operator's perception and expertise, checked statistically."""

import numpy as np
import pytest

from arteleop.ar_features import MODALITIES, ArCues, DisplayFrame
from arteleop.operator import ArmModel, CalibrationPosture
from arteleop.operator.perception import PerceptionParams, perceive
from arteleop.operator.synthetic import Expertise, SyntheticOperator, TaskGeometry
from tests.ar_features.frames import display_frame

P = PerceptionParams()


def _view(cues: ArCues, gripper_in_camera: bool = True) -> DisplayFrame:
    return display_frame(cues=cues, gripper_in_camera=gripper_in_camera)


def _errors(cues: ArCues, n: int = 4000, **kw) -> dict[str, np.ndarray]:
    rng = np.random.default_rng(0)
    view = _view(cues, **kw)
    seen = [perceive(view, P, rng) for _ in range(n)]
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
    rng = np.random.default_rng(1)
    hidden = [
        perceive(_view(MODALITIES["none"], gripper_in_camera=False), P, rng) for _ in range(3000)
    ]
    ghost = [
        perceive(_view(MODALITIES["embodiment"], gripper_in_camera=False), P, rng)
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

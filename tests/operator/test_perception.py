"""The synthetic operator's perception: one function of what is drawn, checked analytically and
statistically against it, layer by layer."""

import dataclasses
import math
from dataclasses import replace

import numpy as np
import pytest

from arteleop.ar_features import (
    DISTANCE_LABEL_STEP_M,
    MODALITIES,
    ArCues,
    DisplayFrame,
    PredictedArm,
)
from arteleop.errors import ConfigurationError
from arteleop.operator import (
    BowlMemory,
    MarkMemory,
    Perceived,
    PerceptionParams,
    PerceptualErrors,
    PickAndPlace,
    perceive,
)
from arteleop.operator.simulated.acuity import (
    ARCMIN_RAD,
    Acuities,
    DisplayGeometry,
    fixations,
    judgement_sd,
    reading_sd_m,
)
from arteleop.operator.simulated.tasks.task import phase_named
from arteleop.scene import BowlSpec
from arteleop.transforms import make_transform
from tests.ar_features.frames import display_frame

P = PerceptionParams()
_EXACT = PerceptionParams(
    display=DisplayGeometry(pixel_rad=0.0), acuities=Acuities(interval_fraction=0, stereo_pixels=0)
)
D, A = P.display, P.acuities
START = ("start",)
"""The marks pointing judges besides the target."""


class _Independent(PerceptualErrors):
    """Every glance a look of its own and no bias, to sample one glance's spread."""

    def __init__(self, seed: int) -> None:
        super().__init__(np.random.default_rng(seed), bias_seed=0, bias_share=0.0)

    def draw(self, stream: str, size: int) -> np.ndarray:
        self.new_look()
        return super().draw(stream, size)

    def draw_fresh(self, stream: str, size: int) -> np.ndarray:
        self.new_look()
        return super().draw_fresh(stream, size)


def _eye_m(view: DisplayFrame, point: np.ndarray) -> float:
    return float(np.linalg.norm(point - view.viewpoint_m))


def _sight(view: DisplayFrame, point: np.ndarray) -> np.ndarray:
    d = point - view.viewpoint_m
    return d / np.linalg.norm(d)


def _grasp_errors(cues: ArCues, n: int = 4000, **kw) -> tuple[DisplayFrame, np.ndarray]:
    """The gripper judged relative to the bowl, minus the truth: (n, 3) m."""
    noise = _independent(0)
    view = display_frame(cues=cues, **kw)
    seen = [perceive(view, P, noise) for _ in range(n)]
    truth = view.gripper_m - view.bowl_m
    return view, np.array([(s.gripper_m - s.bowl_m) - truth for s in seen])


def _independent(seed: int) -> PerceptualErrors:
    return _Independent(seed)


def _split(errors: np.ndarray, axis: np.ndarray) -> tuple[float, float]:
    """SD along ``axis`` and per axis across it."""
    along = errors @ axis
    across = errors - np.outer(along, axis)
    return float(along.std()), float(np.sqrt((across**2).sum(axis=1).mean() / 2))


# -- the one function ----------------------------------------------------------------------------
def test_a_judgement_is_as_fine_as_the_display_and_as_coarse_as_its_interval() -> None:
    """Analytic values: at a zero interval the grain's uniform error; far apart, Weber's law;
    depth from the display's disparity; never finer than the display's pixel."""
    geometry = DisplayGeometry(pixel_rad=2 * ARCMIN_RAD, interocular_m=0.06)
    acuities = Acuities(interval_fraction=0.05, stereo_pixels=0.5)
    zero = judgement_sd(0.0, 1.5, 0.0, geometry, acuities)
    assert zero.across_sd_m == pytest.approx(1.5 * 2 * ARCMIN_RAD / math.sqrt(12))
    assert zero.depth_sd_m == pytest.approx(1.5**2 * ARCMIN_RAD / 0.06)
    far = judgement_sd(2.0, 1.5, 0.0, geometry, acuities)
    assert far.across_sd_m == pytest.approx(math.hypot(0.1, zero.across_sd_m))
    assert far.depth_sd_m == pytest.approx(math.hypot(0.1, zero.depth_sd_m))
    coarse = judgement_sd(0.0, 1.5, 6 * ARCMIN_RAD, geometry, acuities)
    assert coarse.across_sd_m == pytest.approx(3 * zero.across_sd_m)  # the cloud's grain
    assert reading_sd_m(0.001) == pytest.approx(0.001 / math.sqrt(12))


def test_a_fixation_covers_labels_in_the_fovea_and_places_in_the_parafovea() -> None:
    """Analytic cases, seen from the origin at 1 m: places 4 deg apart are seen in one
    fixation, 7 deg apart in two; a label is fixated itself, and covers places near it."""
    eye = np.zeros(3)

    def at(deg: float) -> np.ndarray:
        return np.array([math.sin(math.radians(deg)), 0.0, math.cos(math.radians(deg))])

    para, fovea = math.radians(5), math.radians(1)
    assert fixations([at(0), at(4)], [], eye, para, fovea) == 1
    assert fixations([at(0), at(4), at(7)], [], eye, para, fovea) == 2
    assert fixations([at(0)], [at(3)], eye, para, fovea) == 1  # seen from the label
    assert fixations([at(0)], [at(8)], eye, para, fovea) == 2
    assert fixations([], [at(0), at(1.5)], eye, para, fovea) == 2  # two labels to read
    assert fixations([], [], eye, para, fovea) == 1


def test_a_judgement_takes_the_fixations_of_what_it_combines() -> None:
    """The gripper 3 cm over the grasp point: its place and the grasp point's are seen in one
    fixation, in the cloud or along the beam; the distance bar's label, beside the gripper on
    screen, is read in one more. A marker judged against a bowl across the table takes two."""
    grasp = display_frame().grasp_point_m()
    near = make_transform(np.diag([1.0, -1.0, -1.0]), grasp + [0.0, 0.0, 0.03])
    for cues, expected in ((MODALITIES["none"], 1), (ArCues(beam=True), 1),
                           (MODALITIES["manipulation"], 2)):  # fmt: skip
        seen = perceive(display_frame(cues=cues, T_base_gripper=near), P, _independent(0))
        assert seen.gripper_fixations == expected, cues
    view = display_frame()
    angle = math.acos(_sight(view, view.target_m) @ _sight(view, view.bowl_m))
    assert angle > P.parafovea_rad  # the frame's target and bowl are far apart
    assert perceive(view, P, _independent(0)).target_fixations == 2
    beside = display_frame(target_m=view.bowl_m + [0.02, 0.0, 0.0])
    assert perceive(beside, P, _independent(0)).target_fixations == 1


def test_no_layer_has_a_precision_of_its_own() -> None:
    """Perception's constants are the display's, published acuities and proprioception (not a
    judgement of the display): none names a layer or a cue."""
    names = {f.name for cls in (PerceptionParams, Acuities, DisplayGeometry)
             for f in dataclasses.fields(cls)}  # fmt: skip
    assert names == {"display", "acuities", "proprioception_sd_m", "bias_share", "pixel_rad",
                     "interocular_m", "interval_fraction", "stereo_pixels", "fovea_rad",
                     "parafovea_rad", "eye_movement_s", "mark_drawn_min", "memory_drift_rad",
                     "memory_plateau_s"}  # fmt: skip
    for layer in ("bar", "beam", "mesh", "ghost", "target", "centring"):
        assert not any(layer in name for name in names)


# -- marks the display does not draw ----------------------------------------------------------
def _target_errors(unseen_s: float, drawn: float = 0.0, cues: ArCues = MODALITIES["none"],
                   n: int = 600) -> tuple[np.ndarray, np.ndarray]:  # fmt: skip
    """The target judged, in the table's plane, by ``n`` people who saw it drawn at 0 s and
    look again ``unseen_s`` later at a frame that draws the share ``drawn`` of it: (n, 2) errors
    (m) and the last one's believed SD per axis (m)."""
    shown = display_frame(cues=cues, time_s=0.0)
    later = display_frame(cues=cues, time_s=unseen_s, target_drawn=drawn)
    errors, sd = [], 0.0
    for seed in range(n):
        noise, marks = _independent(seed), MarkMemory(P)
        perceive(shown, P, noise, marks=marks)
        seen = perceive(later, P, noise, marks=marks)
        errors.append((seen.target_m - later.target_m)[:2])
        sd = math.sqrt(seen.target_cov[0, 0])
    return np.array(errors), sd


def test_a_target_the_cloud_does_not_draw_is_judged_worse_the_longer_it_is_unseen() -> None:
    in_view, sd_in_view = _target_errors(12.0, drawn=1.0)
    spread = {s: _target_errors(s)[0].std() for s in (0.0, 2.0, 12.0, 20.0, 40.0)}
    # From memory, with no time unseen, as the glance that saw it; then the drift's SD grows
    # with the root of the time unseen, up to its plateau, past which it no longer grows.
    assert spread[0.0] == pytest.approx(in_view.std(), rel=0.15)
    eye = _eye_m(display_frame(), display_frame().target_m)
    for unseen_s in (2.0, 12.0, 20.0):
        drift = P.memory_drift_rad * eye * math.sqrt(unseen_s)
        assert spread[unseen_s] == pytest.approx(math.hypot(spread[0.0], drift), rel=0.15)
    assert spread[40.0] == pytest.approx(spread[20.0], rel=0.15)
    # The person knows its memory fades: the believed variance grows by the drift's.
    drift = P.memory_drift_rad * eye * math.sqrt(12.0)
    assert _target_errors(12.0, n=1)[1] == pytest.approx(math.hypot(sd_in_view, drift), rel=0.05)


def test_a_target_half_drawn_is_seen_and_the_target_mesh_is_always_drawn() -> None:
    in_view = _target_errors(12.0, drawn=1.0)[0].std()
    assert _target_errors(12.0, drawn=P.mark_drawn_min)[0].std() == pytest.approx(in_view, rel=0.15)
    mesh = MODALITIES["full"]
    assert _target_errors(12.0, drawn=0.0, cues=mesh)[0].std() == pytest.approx(
        _target_errors(12.0, drawn=1.0, cues=mesh)[0].std(), rel=0.15
    )


def test_a_target_never_seen_in_the_trial_is_judged_where_it_is_drawn() -> None:
    hidden = display_frame(time_s=5.0, target_drawn=0.0)
    errors = [perceive(hidden, P, _independent(k)).target_m - hidden.target_m for k in range(300)]
    in_view, _ = _target_errors(0.0, drawn=1.0, n=300)
    assert np.std(np.array(errors)[:, :2]) == pytest.approx(in_view.std(), rel=0.15)


# -- layer by layer, against the function -------------------------------------------------------
def test_in_the_cloud_alone_the_gripper_is_judged_in_stereo_against_the_grasp_point() -> None:
    view, errors = _grasp_errors(MODALITIES["none"])
    interval = float(np.linalg.norm(view.gripper_m - view.grasp_point_m()))
    sd = judgement_sd(interval, _eye_m(view, view.gripper_m), 0.0, D, A)
    along, across = _split(errors, _sight(view, view.gripper_m))
    assert along == pytest.approx(sd.depth_sd_m, rel=0.05)
    assert across == pytest.approx(sd.across_sd_m, rel=0.05)


def test_the_bar_is_read_to_its_label_and_the_beam_drawn_at_the_display_grain() -> None:
    view, errors = _grasp_errors(MODALITIES["manipulation"])
    beam = view.gripper_m - view.grasp_point_m()
    along, across = _split(errors, beam / np.linalg.norm(beam))
    assert along == pytest.approx(DISTANCE_LABEL_STEP_M / math.sqrt(12), rel=0.05)
    sd = judgement_sd(float(np.linalg.norm(beam)), _eye_m(view, view.gripper_m), 0.0, D, A)
    assert across == pytest.approx(sd.across_sd_m, rel=0.05)
    # The label's reading, not stereo, gives the depth along the beam: 19 times finer here.
    assert along < sd.depth_sd_m / 15


def test_a_coarser_cloud_coarsens_what_is_judged_in_it_and_not_the_beam() -> None:
    """The grain comes from what is drawn: a cloud decimated to 4 display pixels a point makes
    a near judgement in it 4 times coarser; the beam is drawn at the display's own pixel."""
    near = {"T_base_gripper": display_frame().T_base_gripper.copy()}
    near["T_base_gripper"][:3, 3] = display_frame().grasp_point_m() + [0.0, 0.0, 0.001]
    cloud = {
        "cloud_points_m": np.zeros((1, 3), np.float32),
        "cloud_colors": np.zeros((1, 3), np.uint8),
        "cloud_spacing_rad": 4 * D.pixel_rad,
    }
    for cues, coarser in ((MODALITIES["none"], True), (ArCues(beam=True), False)):
        _, fine = _grasp_errors(cues, n=1500, **near)
        _, coarse = _grasp_errors(cues, n=1500, **near, **cloud)
        view = display_frame(**near)
        ratio = (
            _split(coarse, _sight(view, view.gripper_m))[1]
            / _split(fine, _sight(view, view.gripper_m))[1]
        )
        assert ratio == pytest.approx(4.0 if coarser else 1.0, rel=0.1)


def test_target_mesh_turns_placement_into_a_coincidence_judgement() -> None:
    """With the mesh, the target relative to the bowl errs as the offset's judgement at the
    display's grain; without it, by the marker against the bowl, centred by eye, far more."""

    def target_vs_bowl(cues: ArCues, **kw) -> tuple[DisplayFrame, np.ndarray]:
        noise = _independent(3)
        view = display_frame(cues=cues, **kw)
        seen = [perceive(view, P, noise) for _ in range(2500)]
        truth = (view.target_m - view.bowl_m)[:2]
        return view, np.array([(s.target_m - s.bowl_m)[:2] - truth for s in seen])

    view, with_mesh = target_vs_bowl(MODALITIES["task"])
    offset = float(np.linalg.norm((view.bowl_m - view.target_m)[:2]))
    sd = judgement_sd(offset, _eye_m(view, view.target_m), 0.0, D, A).across_sd_m
    np.testing.assert_allclose(with_mesh.std(axis=0), sd, rtol=0.05)
    # Near the target, the mesh's judgement is fine and the marker's far coarser.
    near = view.target_m + [0.0, -0.02, 0.0]
    _, mesh_near = target_vs_bowl(MODALITIES["task"], bowl_m=near)
    _, marker_near = target_vs_bowl(MODALITIES["none"], bowl_m=near)
    assert np.all(marker_near.std(axis=0) > 2.5 * mesh_near.std(axis=0))
    # Coinciding, the mesh's judgement is the display's grain alone.
    _, on_it = target_vs_bowl(MODALITIES["task"], bowl_m=view.target_m.copy())
    grain = _eye_m(view, view.target_m) * D.pixel_rad / math.sqrt(12)
    np.testing.assert_allclose(on_it.std(axis=0), grain, rtol=0.05)


def test_the_mesh_guides_the_gripper_while_the_arm_hides_the_bowl() -> None:
    """With the bowl in hand hidden, the mesh is judged against the gripper a grasp radius
    beside it; without the mesh, the marker against the gripper and centred by eye."""
    noise = _independent(4)
    for cues in (MODALITIES["task"], MODALITIES["none"]):
        view = display_frame(cues=cues, bowl_m=None)
        seen = [perceive(view, P, noise) for _ in range(4000)]
        relative = np.array(
            [(s.target_m - s.gripper_m)[:2] - (view.target_m - view.gripper_m)[:2] for s in seen]
        )
        mesh = judgement_sd(view.grasp_radius_m, _eye_m(view, view.target_m), 0.0, D, A)
        if cues.target_mesh:
            np.testing.assert_allclose(relative.std(axis=0), mesh.across_sd_m, rtol=0.06)
            np.testing.assert_allclose(np.diag(seen[0].target_cov)[:2], mesh.across_sd_m**2)
        else:
            assert np.all(relative.std(axis=0) > 2 * mesh.across_sd_m)
        assert seen[0].target_by_gripper  # the bowl's place in the hand adds its uncertainty


def test_a_bowl_the_display_does_not_show_is_not_perceived() -> None:
    noise = _independent(2)
    view = display_frame(cues=MODALITIES["full"], bowl_m=None)
    seen = [perceive(view, P, noise) for _ in range(4000)]
    assert all(s.bowl_m is None for s in seen)
    # No bar or beam without a tracked bowl: the gripper from the cloud, against the target.
    err = np.array([s.gripper_m - view.gripper_m for s in seen])
    interval = float(np.linalg.norm(view.gripper_m - view.target_m))
    sd = judgement_sd(interval, _eye_m(view, view.gripper_m), 0.0, D, A)
    along, across = _split(err, _sight(view, view.gripper_m))
    assert along == pytest.approx(sd.depth_sd_m, rel=0.05)
    assert across == pytest.approx(sd.across_sd_m, rel=0.05)


def test_ghost_shows_a_gripper_the_camera_cannot() -> None:
    noise = _independent(1)
    hidden = [perceive(display_frame(cues=MODALITIES["none"], gripper_in_camera=False), P, noise)
              for _ in range(1500)]  # fmt: skip
    ghost = [
        perceive(display_frame(cues=MODALITIES["embodiment"], gripper_in_camera=False), P, noise)
        for _ in range(1500)
    ]
    assert not hidden[0].gripper_seen and ghost[0].gripper_seen
    err_hidden = np.std([s.gripper_m - display_frame().gripper_m for s in hidden], axis=0)
    np.testing.assert_allclose(err_hidden, P.proprioception_sd_m, rtol=0.1)  # from one's own arm
    assert not hidden[0].closure_known and ghost[0].closure_known


def test_a_task_that_aims_the_gripper_judges_the_target_against_it() -> None:
    """Pointing: the circle is judged against the gripper 5 cm above it, one fixation, not
    against the bowl across the table: about 5 times finer here; exact perception with a depth
    scale of 0.8 shortens that interval's line-of-sight part by 20 %, once."""
    target = display_frame().target_m
    over = make_transform(np.diag([1.0, -1.0, -1.0]), target + [0.0, 0.0, 0.05])
    view = display_frame(T_base_gripper=over)
    truth = view.target_m - view.gripper_m

    def spread(aims: bool) -> float:
        noise = _independent(1)
        seen = [perceive(view, P, noise, aims_gripper=aims) for _ in range(2000)]
        errors = np.array([(s.target_m - s.gripper_m - truth)[:2] for s in seen])
        return float(np.sqrt((errors**2).sum(axis=1).mean()))

    assert spread(True) < spread(False) / 4
    assert perceive(view, P, _independent(0), aims_gripper=True).target_fixations == 1
    scaled = perceive(view, _EXACT, _independent(0), depth_scale=0.8, aims_gripper=True)
    d = _sight(view, view.target_m)
    np.testing.assert_allclose(
        scaled.target_m - scaled.gripper_m, truth - 0.2 * (truth @ d) * d, atol=1e-12
    )


def test_a_persons_depth_scale_stretches_depth_intervals_unknown_to_the_person() -> None:
    """Exact perception but a depth scale of 0.8: the gripper is judged 20 % of the interval's
    line-of-sight part nearer the grasp point along the line of sight, and the believed
    covariance does not change. With the bar, the label gives that interval: no error."""
    exact = _EXACT
    view = display_frame(cues=MODALITIES["none"])
    true = perceive(view, exact, _independent(0))
    scaled = perceive(view, exact, _independent(0), depth_scale=0.8)
    d = _sight(view, view.gripper_m)
    interval = view.gripper_m - view.grasp_point_m()
    expected = -0.2 * (interval @ d) * d
    np.testing.assert_allclose(
        (scaled.gripper_m - scaled.bowl_m) - (true.gripper_m - true.bowl_m), expected, atol=1e-12
    )
    np.testing.assert_array_equal(scaled.gripper_cov, true.gripper_cov)
    bar = display_frame(cues=MODALITIES["manipulation"])
    read = perceive(bar, exact, _independent(0))
    read_scaled = perceive(bar, exact, _independent(0), depth_scale=0.8)
    along = (read_scaled.gripper_m - read_scaled.bowl_m) - (read.gripper_m - read.bowl_m)
    beam = (bar.gripper_m - bar.grasp_point_m()) / np.linalg.norm(interval)
    assert abs(along @ beam) < 1e-12
    # Pointing (no bowl): the marker against the gripper, the interval stretched once.
    point = display_frame(cues=MODALITIES["none"], bowl_m=None)
    true = perceive(point, exact, _independent(0))
    scaled = perceive(point, exact, _independent(0), depth_scale=0.8)
    d = _sight(point, point.target_m)
    expected = -0.2 * ((point.target_m - point.gripper_m) @ d) * d
    np.testing.assert_allclose(
        (scaled.target_m - scaled.gripper_m) - (true.target_m - true.gripper_m),
        expected,
        atol=1e-12,
    )


def test_a_longer_look_averages_a_judgement_of_the_display() -> None:
    """n glances at the same frame divide one glance's variance by n, and the operator's belief
    says so."""
    view = display_frame(cues=MODALITIES["none"])
    looks = []
    for seed in range(1000):
        person = PerceptualErrors(np.random.default_rng(seed), bias_seed=seed, bias_share=0.5)
        for _ in range(4):
            seen = perceive(view, P, person)
        looks.append((seen.gripper_m - seen.bowl_m) - (view.gripper_m - view.bowl_m))
    d = _sight(view, view.gripper_m)
    one = judgement_sd(float(np.linalg.norm(view.gripper_m - view.grasp_point_m())),
                       _eye_m(view, view.gripper_m), 0.0, D, A).depth_sd_m  # fmt: skip
    assert np.std(np.array(looks) @ d) == pytest.approx(one / 2, rel=0.06)
    assert d @ seen.gripper_cov @ d == pytest.approx(one**2 / 4, rel=1e-6)


def test_a_judgement_keeps_its_bias_and_a_longer_look_averages_the_rest() -> None:
    """A proprioceptive stream is bias + fresh noise, variance split by ``bias_share``; n
    glances keep the bias and divide the fresh variance by n, and a new trial of the same person
    errs with the same bias."""
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


# -- memory --------------------------------------------------------------------------------------
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
    # The grasp missed: the bowl is far below the lifted hand.
    assert memory.left_behind(look([0.7, 0.0, 0.1], [0.6, -0.4, -0.2]))
    # Lowered again elsewhere, the hand carries it at the left bowl's height, but far from it.
    assert memory.left_behind(look([0.9, 0.1, 0.0], [0.6, -0.4, -0.2]))
    # Held by its rim, the bowl hangs under the gripper, as far from it as the grasp found it.
    assert not memory.left_behind(look([0.5, -0.3, 0.0], [0.5, -0.3, -0.245]))
    memory.release()
    np.testing.assert_array_equal(memory.bowl_m(look([0.7, 0.0, 0.1], None)), [0.6, -0.4, -0.2])


def test_a_bowl_left_on_the_table_is_gone_back_for_while_lowering_too() -> None:
    """Lowering over the target, the hand is near the table, so a bowl a missed grasp left
    behind is no longer far below it, but a rim's radius away in the plane: reach for it."""
    task = PickAndPlace(BowlSpec().grasp_offset_m(), np.zeros(3))
    eye = np.eye(3) * 1e-4
    at_grasp = Perceived(
        np.array([0.6, -0.32, 0.05]), np.array([0.6, -0.4, 0.0]), np.zeros(3), True, True,
        eye, eye, False,
    )  # fmt: skip
    task.gripped(phase_named(task, "close"), at_grasp)
    lowering = replace(at_grasp, gripper_m=np.array([0.6, -0.12, 0.05]))  # 28 cm on
    carried = replace(lowering, bowl_m=np.array([0.6, -0.2, 0.0]))
    hanging = replace(lowering, bowl_m=np.array([0.6, -0.12, -0.044]))  # under the gripper
    # Each look after a grasp of its own: a setback lets go of the bowl believed in the hand.
    for look, back in ((lowering, "reach"), (carried, None), (hanging, None)):
        task.gripped(phase_named(task, "close"), at_grasp)
        assert task.setback(phase_named(task, "lower"), look) == back


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
    exact = _EXACT
    seen = perceive(view, exact, _independent(1))
    grasp_error = (seen.gripper_m - seen.bowl_m) - (view.gripper_m - true_bowl)
    place_error = (seen.target_m - seen.bowl_m) - (view.target_m - true_bowl)
    # The bar's label is read to its millimetre, whatever the perception.
    label = 5 * DISTANCE_LABEL_STEP_M if MODALITIES[modality].distance_bar else 1e-15
    np.testing.assert_allclose(grasp_error, -s if misled_grasp else 0.0, atol=label)
    np.testing.assert_allclose(place_error, -s if misled_place else 0.0, atol=1e-15)


@pytest.mark.parametrize(
    ("build", "message"),
    [
        (lambda: DisplayGeometry(pixel_rad=0.1),
         "DisplayGeometry.pixel_rad = 0.1: expected 0.0-0.02 (rad)."),
        (lambda: Acuities(interval_fraction=-0.01),
         "Acuities.interval_fraction = -0.01: expected 0.0-0.5 (a fraction of the interval)."),
        (lambda: PerceptionParams(bias_share=2.0),
         "PerceptionParams.bias_share = 2.0: expected 0-1."),
        (lambda: PerceptionParams(eye_movement_s=-0.1),
         "PerceptionParams.eye_movement_s = -0.1: expected 0-1 (s)."),
    ],
)  # fmt: skip
def test_a_perception_constant_out_of_range_is_refused_by_name(build, message: str) -> None:
    with pytest.raises(ConfigurationError) as err:
        build()
    assert str(err.value) == message


def test_a_task_that_aims_the_gripper_judges_the_start_cross_against_it() -> None:
    """Pointing's start: the cross, judged against the gripper 5 cm over it as the target is,
    its centre where its arms cross (nothing to bisect): exact perception gives the truth, a depth
    scale of 0.8 shortens the interval's line-of-sight part by 20 %; across the line of sight a
    glance errs by what :func:`judgement_sd` gives for that interval at the display's pixel. With
    the gripper not shown, the cross is judged against the bowl and the arm is felt: the belief
    holds proprioception's variance. No start is judged unless the task aims the gripper."""
    start = display_frame().target_m + [0.0, -0.2, 0.0]
    over = make_transform(np.diag([1.0, -1.0, -1.0]), start + [0.0, 0.0, 0.05])
    view = display_frame(T_base_gripper=over, start_m=start)
    truth = start - view.gripper_m
    exact = perceive(view, _EXACT, _independent(0), aims_gripper=True, judged=START)
    np.testing.assert_allclose(exact.marks["start"].mark_m - exact.gripper_m, truth, atol=1e-12)
    assert exact.marks["start"].fixations == 1
    scaled = perceive(
        view, _EXACT, _independent(0), depth_scale=0.8, aims_gripper=True, judged=START
    )
    d = _sight(view, start)
    np.testing.assert_allclose(
        scaled.marks["start"].mark_m - scaled.gripper_m, truth - 0.2 * (truth @ d) * d, atol=1e-12
    )
    noise = _independent(1)
    errors = np.array([(s.marks["start"].mark_m - s.gripper_m - truth)
                       for s in (perceive(view, P, noise, aims_gripper=True, judged=START)
                                 for _ in range(1500))])  # fmt: skip
    _, across = _split(errors, d)
    eye = float(np.linalg.norm(start - view.viewpoint_m))
    expected = judgement_sd(0.05, eye, 0.0, D, A).across_sd_m
    assert across == pytest.approx(expected, rel=0.1)
    assert perceive(view, P, _independent(0)).marks == {}  # the task judges no start
    unseen = display_frame(T_base_gripper=over, start_m=start, gripper_in_camera=False)
    felt = perceive(unseen, P, _independent(0), aims_gripper=True, judged=START)
    assert np.all(np.diag(felt.marks["start"].cov) > P.proprioception_sd_m**2)


def _loewner_smaller(a: np.ndarray, b: np.ndarray) -> bool:
    """``a`` is no larger than ``b`` in every direction, and smaller in some."""
    gap = np.linalg.eigvalsh(b - a)
    return bool(gap.min() > -1e-15 and gap.max() > 1e-12)


def test_the_depth_aids_add_the_ring_on_the_table_and_the_height_off_its_label() -> None:
    """With the depth aids drawn, a mark on the table is judged a second time, against the ring
    at the drop line's foot, held to the table's plane; the start's height is read off the label.
    Each judgement is weighed by its precision, so the person believes itself more precise and
    is, as precise as it believes (no bias here); the height errs by the label's rounding. One
    fixation reads the label, 4.5 cm beside the ring, and sees the cross and the gripper in its
    parafovea."""
    start = display_frame().target_m + [0.0, -0.2, 0.0]
    over = make_transform(np.diag([1.0, -1.0, -1.0]), start + [0.0, 0.0, 0.0504])
    plain = display_frame(T_base_gripper=over, start_m=start)
    aided = replace(plain, depth_aids=True)
    truth = start - plain.gripper_m

    def judged(view: DisplayFrame) -> tuple[np.ndarray, Perceived]:
        noise = _independent(2)
        seen = [perceive(view, P, noise, aims_gripper=True, judged=START) for _ in range(3000)]
        return np.array([s.marks["start"].mark_m - s.gripper_m - truth for s in seen]), seen[0]

    errors_plain, one_plain = judged(plain)
    errors_aided, one_aided = judged(aided)
    assert _loewner_smaller(one_aided.marks["start"].cov, one_plain.marks["start"].cov)
    # The height: read off "height 50 mm", 0.4 mm short of the truth, trusted nearly wholly.
    assert one_aided.marks["start"].cov[2, 2] < reading_sd_m(0.001) ** 2
    assert errors_aided[:, 2].mean() == pytest.approx(0.0004, abs=0.0001)
    assert errors_plain[:, 2].std() > 10 * errors_aided[:, 2].std()
    # In the table's plane as precise as believed, and more precise than without the aids; the
    # ring, drawn off the table along the camera's line of sight, shows where the line meets
    # it (drawn straight above it, it biased the judgement 2.2 mm).
    assert np.linalg.norm(errors_aided[:, :2].mean(axis=0)) < 1e-4
    believed = one_aided.marks["start"].cov[:2, :2]
    np.testing.assert_allclose(np.cov(errors_aided[:, :2].T), believed, rtol=0.1, atol=1e-9)
    assert np.trace(np.cov(errors_aided[:, :2].T)) < np.trace(np.cov(errors_plain[:, :2].T))
    assert (one_plain.marks["start"].fixations, one_aided.marks["start"].fixations) == (1, 1)
    # The target, judged in the plane (pointing at it): the ring, no label.
    target = replace(aided, T_base_gripper=make_transform(
        np.diag([1.0, -1.0, -1.0]), aided.target_m + [0.0, 0.0, 0.05]))  # fmt: skip
    pointed = perceive(target, P, _independent(0), aims_gripper=True)
    alone = perceive(replace(target, depth_aids=False), P, _independent(0), aims_gripper=True)
    assert pointed.target_fixations == alone.target_fixations == 1
    assert _loewner_smaller(pointed.target_cov[:2, :2], alone.target_cov[:2, :2])


def test_a_hidden_bowl_is_placed_by_the_gripper_over_the_ring() -> None:
    """The bowl in hand hidden and no mesh: the marker is judged against the gripper, and with
    the aids against the ring as well; without a gripper shown there is no line's top to take
    for it, and the aids add nothing."""
    view = display_frame(cues=MODALITIES["none"], bowl_m=None, depth_aids=True)
    aided = perceive(view, P, _independent(0))
    plain = perceive(replace(view, depth_aids=False), P, _independent(0))
    assert aided.target_by_gripper and plain.target_by_gripper
    assert _loewner_smaller(aided.target_cov[:2, :2], plain.target_cov[:2, :2])
    unseen = replace(view, gripper_in_camera=False)
    felt = perceive(unseen, P, _independent(0))
    felt_plain = perceive(replace(unseen, depth_aids=False), P, _independent(0))
    np.testing.assert_array_equal(felt.target_cov, felt_plain.target_cov)
    np.testing.assert_array_equal(felt.target_m, felt_plain.target_m)


def test_the_drop_line_passing_the_rims_height_guides_the_grasp() -> None:
    """Above the rim, the line passes the rim's height where the gripper, lowered, would be: the
    rim judged against that point, level with it, sharpens the grasp's judgement in the table's
    plane, as precise as believed. Below the rim the line does not pass it."""
    view = display_frame(cues=MODALITIES["none"], depth_aids=True)
    assert view.gripper_m[2] > view.grasp_point_m()[2]
    aided = perceive(view, P, _independent(0))
    plain = perceive(replace(view, depth_aids=False), P, _independent(0))
    assert _loewner_smaller(aided.gripper_cov[:2, :2], plain.gripper_cov[:2, :2])
    noise = _independent(3)
    errors = np.array([(s.gripper_m - s.bowl_m) - (view.gripper_m - view.bowl_m)
                       for s in (perceive(view, P, noise) for _ in range(3000))])  # fmt: skip
    np.testing.assert_allclose(np.cov(errors[:, :2].T), aided.gripper_cov[:2, :2], rtol=0.15)
    low = make_transform(np.diag([1.0, -1.0, -1.0]), view.grasp_point_m() - [0.0, 0.0, 0.01])
    below = replace(view, T_base_gripper=low)
    np.testing.assert_array_equal(perceive(below, P, _independent(0)).gripper_cov,
                                  perceive(replace(below, depth_aids=False), P,
                                           _independent(0)).gripper_cov)  # fmt: skip


def test_through_the_beam_under_the_predictive_ghost_the_gripper_is_the_frames_arm() -> None:
    """The beam and the distance bar hang from the delayed frame's arm, so a gripper judged
    through them is the frame's, not ahead of it by the ghost's lead; a bowl held in that
    frame's hand is where the hand holds it, not left behind by the lead (it was: the lead
    taken off a gripper that never had it)."""
    DOWN = np.diag([1.0, -1.0, -1.0])
    arm = display_frame().T_base_gripper
    ghost = make_transform(DOWN, arm[:3, 3] + [0.0, 0.1, 0.15])  # 18 cm ahead, lifting
    for name, lead in (("full", np.zeros(3)), ("predictive", ghost[:3, 3] - arm[:3, 3])):
        cues = replace(MODALITIES[name], predictive_ghost=True)
        view = display_frame(cues=cues, predicted=PredictedArm(0.2, np.zeros(7), ghost, 0.0))
        seen = perceive(view, P, _independent(0))
        np.testing.assert_allclose(seen.lead_m, lead, atol=1e-12)
        memory = BowlMemory()
        memory.grasp(seen, seen.bowl_m)
        assert not memory.left_behind(seen), name


def test_under_the_predictive_ghost_the_aids_are_judged_from_the_frames_arm() -> None:
    """The line hangs from the delayed frame's arm, 5 cm behind the predictive ghost over the
    start: the person, who sees both, takes the ghost's lead off what the ring and the label
    say, so the aids do not pull the judgement back to the delayed arm (they did, by 25 mm)."""
    start = display_frame().target_m + [0.0, -0.2, 0.0]
    DOWN = np.diag([1.0, -1.0, -1.0])
    ghost = make_transform(DOWN, start + [0.0, 0.0, 0.05])
    arm = make_transform(DOWN, start + [0.0, -0.05, 0.05])
    view = display_frame(cues=MODALITIES["predictive"], T_base_gripper=arm, start_m=start,
                         predicted=PredictedArm(0.2, np.zeros(7), ghost, 0.0),
                         depth_aids=True)  # fmt: skip
    truth = start - ghost[:3, 3]
    noise = _independent(4)
    errors = np.array([s.marks["start"].mark_m - s.gripper_m - truth
                       for s in (perceive(view, P, noise, aims_gripper=True, judged=START)
                                 for _ in range(2000))])  # fmt: skip
    # Unbiased, but for the height's rounding on the label.
    assert np.linalg.norm(errors.mean(axis=0)) < 0.001

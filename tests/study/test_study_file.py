"""Study definitions in TOML: round trips, and errors that name the file, the line and the key."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from arteleop.cli import main
from arteleop.errors import StudyDefinitionError
from arteleop.operator import SeenOutcomes
from arteleop.study import (
    CohortConfig,
    ParticipantSpec,
    StudyConfig,
    first_difference,
    load_study_file,
    parse_study,
    study_text,
)
from arteleop.study.carry import Carried
from arteleop.study.study_constants import OPERATOR_PARAMS_KEYS


def test_the_written_definition_reads_back_as_the_same_study() -> None:
    assert parse_study(study_text(StudyConfig())) == StudyConfig()
    listed = StudyConfig(modalities=("none", "full"), order="listed",
                         orders=(("none", "full"), ("full", "none")))  # fmt: skip
    assert parse_study(study_text(listed)) == listed
    named = StudyConfig(
        seed=7, modalities=("full", "none"), order="cyclic", delay_ms=150.0,
        participants=(ParticipantSpec("S01", avr_hours=3, gender="f"), ParticipantSpec("S02")),
    )  # fmt: skip
    assert parse_study(study_text(named)) == named
    operator = parse_study("[operator]\nmiss_rate = 0.02\n[hand_filter]\nenabled = false\n")
    assert operator.operator.miss_rate == 0.02 and not operator.hand_filter.enabled
    assert parse_study(study_text(operator)) == operator


def test_the_operator_and_filter_tables_reach_the_participants_and_trials() -> None:
    from arteleop.study.plan import plan_study
    from arteleop.study.protocol import operator_traits, trial_config
    from arteleop.study.sites import StudySite

    text = "[familiarization]\ntrials = 0\n"
    default = parse_study(text)
    strict = parse_study(text + "[operator]\nplacement_criterion_m = 0.004\nmiss_rate = 0.01\n"
                         "[hand_filter]\nmin_cutoff_hz = 2.5\n")  # fmt: skip
    person = default.participants or ParticipantSpec("P01")
    before, after = operator_traits(default, person), operator_traits(strict, person)
    # The same draws scaled: the medians move, the person's place in the cohort does not.
    assert after.placement_criterion_m == pytest.approx(before.placement_criterion_m * 0.4)
    assert 1 - after.confidence == pytest.approx((1 - before.confidence) * 0.2)
    spec = plan_study(strict)[0]
    assert trial_config(strict, StudySite(), spec).controller.hand_filter.min_cutoff_hz == 2.5


def test_a_study_changes_a_constant_of_the_model_and_its_file_says_so() -> None:
    """A sensitivity run's file names each changed constant beside the model's value; the
    model's own study files are as before, without the table."""
    from arteleop.operator import OperatorParams

    changed = parse_study("[operator_params]\nmax_look_s = 3.0\ngrip_ramp_s = 0.6\n")
    assert changed.operator_params == replace(OperatorParams(), max_look_s=3.0, grip_ramp_s=0.6)
    text = study_text(changed)
    assert "max_look_s = 3.0  # the model's: 1.5\ngrip_ramp_s = 0.6  # the model's: 0.3\n" in text
    assert parse_study(text) == changed
    assert first_difference(StudyConfig(), changed) == "operator_params.max_look_s"
    assert "operator_params" not in study_text(StudyConfig())
    # What a study file cannot say, a study cannot hold: its run folder would not record it.
    with pytest.raises(StudyDefinitionError, match="a study may change only the plain-number"):
        StudyConfig(operator_params=replace(OperatorParams(), tremor_hz=(5.0, 6.0)))


def test_the_constants_reach_each_trial_and_pointing_block(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """Each planned trial's operator has the study's constants, with the lag it believes
    carried from its last trial; each pointing block begins with them."""
    from arteleop.study import protocol
    from arteleop.study.plan import plan_study
    from arteleop.study.pointing_run import pointing_blocks
    from arteleop.study.sites import StudySite

    class Started(Exception):
        pass

    given = []

    def operator(*_: object, params: object, **__: object) -> None:
        given.append(params)
        raise Started

    monkeypatch.setattr(protocol, "trial_operator", operator)
    study = parse_study("[familiarization]\ntrials = 0\n[operator_params]\nmax_look_s = 3.0\n")
    with pytest.raises(Started):
        protocol.run_planned_trial(study, StudySite(), ParticipantSpec("P01"),
                                   plan_study(study)[0],
                                   Carried(0.4, SeenOutcomes(3, 1)))  # fmt: skip
    carried = {"familiar_lag_s": 0.4, "seen_outcomes": SeenOutcomes(3, 1)}
    assert given == [replace(study.operator_params, **carried)]
    pointing = parse_study('task = "pointing"\n[[conditions]]\ncues = []\n'
                           "[operator_params]\nmax_look_s = 3.0\n")  # fmt: skip
    assert {b.params for b in pointing_blocks(pointing)} == {pointing.operator_params}


def test_study_init_writes_the_commented_default(tmp_path: Path, capsys) -> None:
    path = tmp_path / "study.toml"
    assert main(["study", "init", str(path)]) == 0
    text = path.read_text()
    scheme = "# williams (balanced Latin square), cyclic, random (seeded) or listed (in orders)"
    assert f"{scheme}\norder = " in text
    assert load_study_file(path)[0] == StudyConfig()
    assert main(["study", "init", str(path)]) == 2  # never overwrites
    assert "exists; give a new file name (nothing was written)" in capsys.readouterr().err


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ('seed = 1\nordr = "williams"\n',
         "s.toml line 2: unknown key 'ordr'. Valid keys: name, task, consent, instructions, "
         "questionnaire, seed, modalities, order, "
         "orders, trials_per_modality, timeout_s, delay_ms, depth_aids, camera_offset_mm, "
         "camera_offset_deg, camera_pose, start_xy_m, target_xy_m, familiarization, cohort, "
         "participants, operator, operator_params, hand_filter, conditions, pointing."),
        ("camera_offset_mm = [600, 0, 0]\n",
         "s.toml line 1: camera_offset_mm = [600.0, 0.0, 0.0]: expected three numbers (mm, "
         "camera frame) whose length is at most 500 mm."),
        ("camera_offset_deg = [1, 2]\n",
         "s.toml line 1: camera_offset_deg must be three numbers (x, y, z), got [1, 2]."),
        ("[cohort]\nsize = 3\nsizes = 4\n",
         "s.toml line 3: unknown key 'cohort.sizes'. Valid keys in [cohort]: size, "
         "avr_experts, games_experts, both_experts, movement_time_sd, id_prefix."),
        ('\norder = "latin"\n',
         "s.toml line 2: order = 'latin'; expected one of williams, cyclic, random, listed."),
        ("seed = 1.5\n", "s.toml line 1: seed must be a whole number, got 1.5."),
        ("start_xy_m = [0.68]\n",
         "s.toml line 1: start_xy_m must be two numbers (x, y), got [0.68]."),
        ('modalities = ["none", "ful"]\n',
         "s.toml line 1: modalities = ['none', 'ful']: expected one or more of none, "
         "manipulation, embodiment, task, full, predictive (or AR layers joined by '+')."),
        ("[cohort]\nsize = 5\navr_experts = 7\n",
         "s.toml line 2: cohort: 7 AR/VR experts and 7 gamers, 4 of them both, do not fit 5 "
         "participants: both_experts must not exceed either count, and avr_experts + "
         "games_experts - both_experts must not exceed size."),
        ('[[participants]]\nid = "A"\n[[participants]]\nid = "B"\n[[participants]]\nid = "A"\n',
         "s.toml line 6: participant id 'A' is used twice; each participant needs an id of "
         "their own."),
        ('[[participants]]\nid = "A"\navr_hours = 5\n',
         "s.toml line 3: participant A: avr_hours = 5; expected a bucket 1, 2 or 3."),
        ("trials_per_modality = 2\n",
         "s.toml line 1: trials_per_modality = 2: the study data format "
         "(docs/reference/data-format.md) holds one experimental trial per "
         "participant and modality, so 1 is the only value it can record."),
        ("seed = \n", "s.toml: not valid TOML: Invalid value (at line 1, column 8)."),
        ('modalities = ["none", "full"]\norder = "listed"\norders = [["none", "full"], ["full"]]\n',
         "s.toml line 3: orders = ...: sequence 2, ['full'], must name each of the 2 conditions "
         "['none', 'full'] exactly once."),
        ('orders = [["none", "full"]]\n',
         "s.toml line 1: orders = [['none', 'full']]: give sequences in orders exactly when "
         "order = \"listed\" (order is 'williams')."),
        ("orders = [1, 2]\n", "s.toml line 1: orders must be a list of lists of text, got [1, 2]."),
        ("[operator]\nmiss_rate = 0.01\nplacement_criterion_m = 0.2\n",
         "s.toml line 3: operator.placement_criterion_m = 0.2: expected 0.002-0.05 (m)."),
        ("[operator]\nmiss_rate = 0.5\n",
         "s.toml line 2: operator.miss_rate = 0.5: expected 0.005-0.2 (a probability: 1 - the "
         "confidence)."),
        ("[operator]\nurgency_sd = -1\n",
         "s.toml line 2: operator.urgency_sd = -1.0: expected 0.0-1.0 (the SD of a log)."),
        ("\n[hand_filter]\nbeta_per_m = -5\n",
         "s.toml line 3: hand_filter.beta_per_m = -5.0: expected 0-1000 (Hz per m/s; 0 is a "
         "plain low-pass filter)."),
        ("[hand_filter]\nmin_cutoff_hz = 0\n",
         "s.toml line 2: hand_filter.min_cutoff_hz = 0.0: expected a cutoff of 0.01-100 Hz."),
        ("[operator_params]\nmax_look_s = 0\n",
         "s.toml line 2: operator_params.max_look_s = 0.0: expected > 0."),
        ("\n[operator_params]\nhand_pitch_rad = 2\n",
         "s.toml line 3: operator_params.hand_pitch_rad = 2.0: expected -1.571 to 1.571 (rad: a "
         "quarter turn either way)."),
        ("[operator_params]\nmax_look_s = \"long\"\n",
         "s.toml line 2: operator_params.max_look_s must be a number, got 'long'."),
        ("[operator_params]\nperception = 1\n",
         "s.toml line 2: unknown key 'operator_params.perception'. A study may change these of "
         "the model's constants: " + ", ".join(OPERATOR_PARAMS_KEYS) + "."),
    ],
)  # fmt: skip
def test_bad_definitions_are_refused_naming_line_and_key(text: str, message: str) -> None:
    with pytest.raises(StudyDefinitionError) as err:
        parse_study(text, "s.toml")
    assert str(err.value) == message


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("seed = 1\nstart_xy_m = [0.68, 0.55]\n",
         "line 2: start_xy_m: Workspace.start_xy_m=(0.68, 0.55): a bowl of radius 0.08 m there "
         "overhangs the table, which spans x in [0.350, 1.150] and y in [-0.750, 0.450] m."),
        # On the table and in reach, but below the head camera's image: refused before a run
        # starts, where a trial's site would stop the run at its first trial.
        ("target_xy_m = [0.433, 0.038]\n",
         "line 1: target_xy_m: The head camera can't see the target marker at [0.433, 0.038, "
         "-0.2] m: it projects to pixel (257, 480), outside the 640x480 image (less 10 px at its "
         "edges). Move Workspace.target_xy_m into the camera's view."),
    ],
)  # fmt: skip
def test_a_start_or_target_the_site_would_refuse_is_named_with_its_line(
    tmp_path: Path, text: str, message: str
) -> None:
    path = tmp_path / "s.toml"
    path.write_text(text)
    with pytest.raises(StudyDefinitionError) as err:
        load_study_file(path)
    assert str(err.value) == f"{path} {message}"


def test_a_missing_file_says_how_to_make_one(tmp_path: Path) -> None:
    path = tmp_path / "nope.toml"
    with pytest.raises(StudyDefinitionError, match=r"no such study file. 'arteleop study init"):
        load_study_file(path)


def test_first_difference_names_the_dotted_key() -> None:
    a = StudyConfig()
    assert first_difference(a, StudyConfig()) is None
    assert first_difference(a, StudyConfig(seed=1)) == "seed"
    fewer = CohortConfig(size=10, avr_experts=3, games_experts=3, both_experts=1)
    assert first_difference(a, StudyConfig(cohort=fewer)) == "cohort.size"


def test_a_mis_registered_camera_reaches_every_trial_of_the_study() -> None:
    from arteleop.study.plan import plan_study
    from arteleop.study.protocol import trial_config
    from arteleop.study.sites import StudySite

    study = parse_study(
        "camera_offset_mm = [10, 0, -5]\ncamera_offset_deg = [0, 0.5, 0]\n"
        "[familiarization]\ntrials = 0\n",
        "s.toml",
    )
    site = StudySite()
    specs = plan_study(study)
    cameras = {trial_config(study, site, spec).site.camera for spec in specs}
    assert len(specs) == 110 and len(cameras) == 1
    (camera,) = cameras
    assert camera.registration_offset_mm == (10.0, 0.0, -5.0)
    assert camera.registration_offset_deg == (0.0, 0.5, 0.0)


def test_a_calibrated_camera_pose_comes_from_a_graph_file(tmp_path: Path) -> None:
    """camera_graph names the file 'arteleop calibrate' writes, relative to the study file; the
    run folder's copy of the definition holds the pose itself, so it stands alone."""
    from arteleop.frames import EdgeKind, TransformGraph
    from arteleop.study.plan import plan_study
    from arteleop.study.protocol import trial_config
    from arteleop.study.sites import StudySite

    T = np.eye(4)
    T[:3, :3] = [[0.0, -1.0, 0.0], [0.0, 0.0, -1.0], [1.0, 0.0, 0.0]]
    T[:3, 3] = [0.1, -0.2, 0.8]
    graph = TransformGraph()
    graph.set("base", "head_camera", T, EdgeKind.CALIBRATION)
    (tmp_path / "cal").mkdir()
    graph.save(tmp_path / "cal" / "c.json")
    path = tmp_path / "s.toml"
    path.write_text('camera_graph = "cal/c.json"\n[familiarization]\ntrials = 0\n')
    study, _ = load_study_file(path)
    np.testing.assert_array_equal(study.camera_pose, T)
    assert parse_study(study_text(study)) == study
    camera = trial_config(study, StudySite(), plan_study(study)[0]).site.camera
    np.testing.assert_array_equal(camera.registered_pose, T)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        (
            'camera_graph = "nothing.json"\n',
            "s.toml line 1: camera_graph: {tmp}/nothing.json: cannot read the graph file (No "
            "such file or directory). 'arteleop calibrate --out nothing.json' writes such a file.",
        ),
        (
            'camera_graph = "g.json"\n',
            "s.toml line 1: camera_graph: no frame 'head_camera' in the graph; its frames are "
            "['base', 'table']. 'arteleop calibrate --out g.json' writes such a file.",
        ),
        (
            'camera_graph = "g.json"\ncamera_offset_mm = [5, 0, 0]\n',
            "s.toml line 1: camera_graph and camera_offset_mm: the graph's pose replaces them; "
            "give one or the other.",
        ),
        (
            'camera_graph = "g.json"\ncamera_pose = []\n',
            "s.toml line 1: camera_graph and camera_pose: the graph's pose replaces them; give "
            "one or the other.",
        ),
        (
            "camera_pose = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]]\n",
            "s.toml line 1: camera_pose = [[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, "
            "1.0, 0.0]]: expected 4 rows of 4 numbers, a rigid transform (m), and no "
            "camera_offset_mm or camera_offset_deg beside it.",
        ),
        (
            'camera_pose = [["a"]]\n',
            "s.toml line 1: camera_pose must be a list of lists of numbers, got [['a']].",
        ),
    ],
)
def test_bad_camera_poses_are_refused(tmp_path: Path, text: str, message: str) -> None:
    from arteleop.frames import EdgeKind, TransformGraph

    graph = TransformGraph()
    graph.set("base", "table", np.eye(4), EdgeKind.FIXED)
    graph.save(tmp_path / "g.json")
    path = tmp_path / "s.toml"
    path.write_text(text)
    with pytest.raises(StudyDefinitionError) as err:
        load_study_file(path)
    assert str(err.value) == message.format(tmp=tmp_path).replace("s.toml", str(path))

"""The default study's plan: the original's cohort, its counterbalancing, reachable practice."""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterator

import numpy as np
import pytest

from arteleop.scene import RemoteSite, SiteConfig
from arteleop.study import (
    MODALITY_NAMES,
    StudyConfig,
    StudySite,
    participants,
    plan_study,
)


@pytest.fixture(scope="module")
def study_site() -> Iterator[StudySite]:
    site = StudySite()
    yield site
    site.close()


def test_the_default_cohort_has_the_original_expertise() -> None:
    people = participants(StudyConfig())
    assert len(people) == 22 and len({p.id for p in people}) == 22
    avr = {p.id for p in people if p.avr_hours >= 2}
    games = {p.id for p in people if p.games_hours >= 2}
    assert (len(avr), len(games), len(avr & games)) == (7, 7, 4)
    assert all(p.avr_experience >= 5 for p in people if p.id in avr)
    assert participants(StudyConfig()) == people  # seeded
    assert participants(StudyConfig(seed=1)) != people


def test_the_plan_counterbalances_and_seeds_every_trial(study_site: StudySite) -> None:
    study = StudyConfig()
    plan = plan_study(study, study_site.practice_points(study.start_xy_m, study.target_xy_m))
    assert len(plan) == 22 * (3 + 5)
    assert len({spec.seed for spec in plan}) == len(plan)
    experimental = [s for s in plan if s.phase == "experimental"]
    for person in {s.participant for s in plan}:
        own = [s for s in experimental if s.participant == person]
        assert sorted(s.modality for s in own) == sorted(MODALITY_NAMES)
        assert [s.position for s in own] == [1, 2, 3, 4, 5]
        assert [s.trial_index for s in own] == [4, 5, 6, 7, 8]
    first_positions = Counter(s.modality for s in experimental if s.position == 1)
    assert sorted(first_positions.values()) == [4, 4, 4, 5, 5]  # 22 over a 10-row square
    assert {(s.start_xy_m, s.target_xy_m) for s in experimental} == {((0.68, -0.45), (0.68, -0.1))}
    practice = [s for s in plan if s.phase == "familiarization"]
    assert all(s.modality == "none" for s in practice)
    assert len({(s.start_xy_m, s.target_xy_m) for s in practice}) == len(practice)
    for s in practice:  # the site would accept every practice position, and the camera sees it
        assert study_site.problem(s.start_xy_m, s.target_xy_m) is None
        assert study_site.seen_at_rest(s.start_xy_m)
    # The table's near left corner is out of the head camera's image.
    assert not study_site.seen_at_rest((0.45, 0.30))
    assert study_site.seen_at_rest(study.start_xy_m)
    again = plan_study(study, study_site.practice_points(study.start_xy_m, study.target_xy_m))
    assert again == plan


def test_listed_orders_are_taken_in_turn(study_site: StudySite) -> None:
    from arteleop.study import FamiliarizationConfig

    study = StudyConfig(modalities=("none", "task", "full"), order="listed",
                        orders=(("full", "none", "task"), ("task", "full", "none")),
                        familiarization=FamiliarizationConfig(trials=0))  # fmt: skip
    plan = plan_study(study)
    firsts = [s.modality for s in plan if s.position == 1]
    assert firsts[:4] == ["full", "task", "full", "task"]


def test_out_of_reach_points_are_named(study_site: StudySite) -> None:
    problem = study_site.problem((0.68, -0.45), (0.95, -0.10))
    assert problem is not None and problem.startswith("The target point (0.95, -0.1) m is out of")


def test_practice_points_are_where_every_trials_site_sees_its_landmarks(
    study_site: StudySite,
) -> None:
    # The study's camera pose comes from pinocchio, a trial site's from PyBullet.
    with RemoteSite(SiteConfig()) as site:
        T_site = site.camera.geometry.T_base_camera
    assert np.abs(study_site.camera.T_base_camera - T_site).max() <= 1e-9
    # The tracker's model finds a bowl at the image's bottom edge, but its start marker lies
    # outside the image less its margin, where a trial's site stops the run: practice skips it.
    edge = (0.433, 0.038)
    assert study_site.seen_at_rest(edge)
    assert study_site.problem(edge, (0.68, -0.1)) == (
        "The head camera can't see the start marker at [0.433, 0.038, -0.2] m: it projects to "
        "pixel (257, 480), outside the 640x480 image (less 10 px at its edges). Move "
        "Workspace.start_xy_m into the camera's view."
    )

"""The models of what the camera sees against rendered frames, over seeded trials: the bowl
tracker's (against the tracker itself) and the marks on the table's (against the pixels)."""

import numpy as np
import pytest

from arteleop.scene import (
    BowlSight,
    BowlTracker,
    HeadCameraConfig,
    RemoteSite,
    RGBDFrame,
    SiteConfig,
    start_line_m,
    target_line_m,
)
from arteleop.teleop import TrialConfig, TrialProgress, run_trial, trial_operator
from tests.parallel import run_each

UNTIL_S = 60.0
"""Seeds 0 and 1 under ``none`` reach, grasp, lift, carry and lower the bowl by then; the arm
hides it from the grasp on."""
SEEDS = (0, 1, 2)
EVERY_S = 0.5


@pytest.fixture(scope="module")
def looks(site_config: SiteConfig) -> np.ndarray:
    """(time, model found, tracker found, tracker's error to the truth (m), gripper's distance
    from the bowl's rim in the table's plane (m), the target circle's share drawn by the model
    and in the rendered frame, the start cross's likewise) every 0.5 s."""
    runs = run_each(_looks, [(site_config, seed) for seed in SEEDS])
    return np.array([row for rows in runs for row in rows], dtype=float)


def _looks(site_config: SiteConfig, seed: int) -> list[tuple[float, ...]]:
    small = HeadCameraConfig(width_px=320, height_px=240)
    config = TrialConfig(modality="none", seed=seed, timeout_s=UNTIL_S, site=site_config)
    rows: list[tuple[float, ...]] = []
    with RemoteSite(SiteConfig(robot=site_config.robot, camera=small)) as site:
        tracker = BowlTracker(site.config.workspace.bowl)
        z = site.config.workspace.table_top_z_m
        lines = target_line_m(site.config.workspace), start_line_m(site.config.workspace)

        def look(status: TrialProgress) -> None:
            t = status.time_s
            if round(t * 30) % round(EVERY_S * 30):
                return
            model = site.sight_bowl()
            rgbd = site.capture()
            track = tracker.track(rgbd, z)
            state = site.observe()
            error = np.linalg.norm(track.position_m - state.bowl_m) if track.found else np.nan
            axis = np.hypot(*(state.gripper_m - state.bowl_m)[:2])
            rim = site.config.workspace.bowl.rim_radius_m
            marks = site.sight_marks()
            drawn = [_drawn_share(site, rgbd, line) for line in lines]
            rows.append((t, model.found, track.found, error, axis - rim,
                         marks.target_share, drawn[0], marks.start_share, drawn[1]))  # fmt: skip

        run_trial(trial_operator(site, config), config, site, progress=look)
    return rows


def _drawn_share(site: RemoteSite, rgbd: RGBDFrame, line_m: np.ndarray) -> float:
    """The share of a mark's points that the rendered frame draws: the pixel each falls on is
    the marker's dark colour at the table's depth there."""
    drawn = 0
    for point in line_m:
        u, v, z = site.camera.geometry.locate(point)
        col, row = round(u), round(v)
        if 0 <= row < rgbd.depth_m.shape[0] and 0 <= col < rgbd.depth_m.shape[1]:
            at_table = abs(float(rgbd.depth_m[row, col]) - z) < 0.015
            drawn += at_table and int(rgbd.rgb[row, col].max()) < 60
    return drawn / len(line_m)


def test_the_trial_hides_and_shows_the_bowl(looks: np.ndarray) -> None:
    found = looks[:, 2].astype(bool)
    assert 0.2 < found.mean() < 0.9  # premise: both cases occur often


def test_the_model_finds_the_bowl_when_the_tracker_does(looks: np.ndarray) -> None:
    model, tracker = looks[:, 1].astype(bool), looks[:, 2].astype(bool)
    # 98.6 % here (215 looks), 99.0 % over 30 whole trials (benchmarks/bench_bowl_sight.py,
    # which fitted the threshold); a change anywhere in the loop gives other trials. What
    # disagreement is left is the model finding a partly hidden bowl, which the tracker
    # refuses (bowl_sight.py).
    assert (model == tracker).mean() >= 0.95
    # It may hide a bowl the tracker finds only while the gripper hovers over the rim before
    # the grasp, the bowl partly behind it (the tracker still fits the arc it sees): none of
    # 74 finds here, 1 of 760 over the 30 trials. Nowhere else.
    hidden = tracker & ~model
    over_rim = np.abs(looks[:, 4]) < 0.05
    assert not (hidden & ~over_rim).any()
    assert hidden.sum() <= tracker.sum() / 20


def test_the_marks_model_draws_what_the_rendered_frame_draws(looks: np.ndarray) -> None:
    model, rendered = looks[:, [5, 7]], looks[:, [6, 8]]
    # Premise: the arm and the bowl hide each mark in some looks and not in others.
    assert ((model < 0.5).mean(axis=0) > 0.1).all() and ((model == 1).mean(axis=0) > 0.1).all()
    apart = np.abs(model - rendered)
    # The target circle, point by point but at an edge passing over it (one look of 157 more
    # than a tenth apart here, 0.29 as the arm came over it; 0.3 % of points apart on average).
    assert apart[:, 0].mean() < 0.02 and (apart[:, 0] > 0.1).mean() < 0.05
    # The start cross lies behind the right shoulder, whose drawn mesh is wider than its
    # collision mesh (the rays' only geometry): there the model draws what the frame hides,
    # and the other way round only where an edge passes over it (one look of 139 here, 3 of its
    # 24 points as the arm came over; mark_sight.py).
    hides = rendered[:, 1] - model[:, 1]
    assert (hides > 0.1).mean() < 0.02 and hides.max() <= 0.2


def test_the_models_position_is_within_the_trackers_error(looks: np.ndarray) -> None:
    # The model reports the true position: its error against the tracker is the tracker's.
    errors = looks[:, 3][looks[:, 1].astype(bool) & looks[:, 2].astype(bool)]
    assert np.median(errors) <= 0.005


@pytest.mark.parametrize("xy_m", [(0.5, 0.0), (0.55, -0.45), (0.6, -0.3), (0.68, -0.45)])
def test_with_the_arm_at_rest_the_model_sees_what_the_tracker_sees(
    site_config: SiteConfig, xy_m: tuple[float, float]
) -> None:
    # Nothing hides the bowl here: the tracker finds it, and the model's rays reach most of
    # its points (the inside and the near wall; the far wall's outside faces away). Before
    # the head's collision spheres left the URDF, the first three saw none, their rays
    # stopped 4-6 cm from the camera.
    small = HeadCameraConfig(width_px=320, height_px=240)
    with RemoteSite(SiteConfig(robot=site_config.robot, camera=small)) as site:
        site.place_bowl(xy_m)
        model = site.sight_bowl()
        track = BowlTracker(site.config.workspace.bowl).track(
            site.capture(), site.config.workspace.table_top_z_m
        )
        n_points = BowlSight(site.config.workspace.bowl).n_surface_points
    assert track.found
    assert model.found
    assert model.n_points >= n_points / 2

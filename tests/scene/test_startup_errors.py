"""Every bad configuration stops the site at start-up with a message that says what to change."""

from dataclasses import replace

import numpy as np
import pytest

from arteleop.errors import CameraConfigError, ConfigurationError, WorkspaceError
from arteleop.scene import BowlSpec, HeadCameraConfig, RemoteSite, SiteConfig, Workspace


def test_target_out_of_reach(site_config: SiteConfig) -> None:
    ws = Workspace(table_center_xy_m=(0.95, -0.15), target_xy_m=(1.2, -0.1))
    with pytest.raises(
        WorkspaceError, match=r"target point \(1.2, -0.1\) m is out of the right arm's reach"
    ):
        RemoteSite(replace(site_config, workspace=ws))


def test_start_too_close_to_the_body(site_config: SiteConfig) -> None:
    ws = Workspace(table_center_xy_m=(0.55, -0.15), start_xy_m=(0.25, -0.3))
    with pytest.raises(WorkspaceError, match=r"start point .* Move Workspace.start_xy_m"):
        RemoteSite(replace(site_config, workspace=ws))


@pytest.mark.parametrize("thickness_m", [0.0003, 0.04])
def test_bowl_the_gripper_cannot_span(site_config: SiteConfig, thickness_m: float) -> None:
    ws = Workspace(
        bowl=BowlSpec(wall_thickness_m=thickness_m, bottom_diameter_m=0.1, height_m=0.09)
    )
    with pytest.raises(
        WorkspaceError, match=r"can't pinch a bowl wall .* pads close to 0.5 mm and open to 42.2 mm"
    ):
        RemoteSite(replace(site_config, workspace=ws))


def test_camera_that_does_not_see_the_table(site_config: SiteConfig) -> None:
    cam = HeadCameraConfig(pitch_down_deg=-10.0)
    with pytest.raises(
        CameraConfigError, match=r"can't see the start marker .* Adjust HeadCameraConfig"
    ):
        RemoteSite(replace(site_config, camera=cam))


def test_the_smallest_image_allowed_starts_a_site(site_config: SiteConfig) -> None:
    # The landmarks' margin is a share of the image (10 px of 640), not 10 px of every image.
    cam = HeadCameraConfig(width_px=8, height_px=8)
    with RemoteSite(replace(site_config, camera=cam)) as site:
        assert site.camera.geometry.sees(site.config.workspace.start_m)


def test_camera_too_close_for_its_depth_range(site_config: SiteConfig) -> None:
    cam = HeadCameraConfig(min_depth_m=1.6, max_depth_m=4.0)
    with pytest.raises(CameraConfigError, match=r"outside the depth range \[1.6, 4.0\] m"):
        RemoteSite(replace(site_config, camera=cam))


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        (
            {"start_xy_m": (2.0, 0.0)},
            r"start_xy_m=\(2.0, 0.0\): a bowl of radius 0.08 m there overhangs the table",
        ),
        ({"target_xy_m": (0.70, -0.43)}, "apart, less than the bowl's diameter"),
        ({"target_xy_m": (float("nan"), 0.0)}, "must be two finite numbers"),
        (
            {"bowl_xy_m": (0.68, 0.5)},
            r"bowl_xy_m=\(0.68, 0.5\): a bowl of radius 0.08 m there overhangs the table",
        ),
        # The bowl moved away from the cross: its own start is what must be apart from the
        # target.
        ({"bowl_xy_m": (0.75, -0.15), "target_xy_m": (0.70, -0.05)}, "apart, less than"),
    ],
)
def test_bad_workspace(kwargs: dict, message: str) -> None:
    with pytest.raises(WorkspaceError, match=message):
        Workspace(**kwargs)


def test_a_bowl_away_from_the_start_cross_starts_where_it_is_put(site_config: SiteConfig) -> None:
    """Pointing's scene: the cross at the start, the bowl out of the way; the gap to the
    target is the bowl's, so a start 10 cm from the target is allowed."""
    ws = Workspace(start_xy_m=(0.68, -0.45), target_xy_m=(0.68, -0.35), bowl_xy_m=(0.45, -0.65))
    with RemoteSite(replace(site_config, workspace=ws)) as site:
        np.testing.assert_allclose(site.observe().T_base_bowl[:2, 3], (0.45, -0.65), atol=2e-3)
        seen = site.sight_bowl()
        assert seen.found
        np.testing.assert_allclose(seen.position_m[:2], (0.45, -0.65), atol=5e-3)


def test_failed_start_up_releases_the_physics_client(site_config: SiteConfig) -> None:
    import pybullet as p

    before = sum(p.isConnected(i) for i in range(16))
    with pytest.raises(CameraConfigError):
        RemoteSite(replace(site_config, camera=HeadCameraConfig(pitch_down_deg=-10.0)))
    assert sum(p.isConnected(i) for i in range(16)) == before


@pytest.mark.parametrize("iterations", [0, -3, 2.5, True])
def test_bad_solver_iterations(iterations: object) -> None:
    with pytest.raises(
        ConfigurationError, match=rf"solver_iterations={iterations!r}: use a whole number >= 1"
    ):
        SiteConfig(solver_iterations=iterations)  # type: ignore[arg-type]


@pytest.mark.parametrize("iterations", [50, 12])
def test_the_solver_runs_the_iterations_asked_for(site_config: SiteConfig, iterations: int) -> None:
    with RemoteSite(replace(site_config, solver_iterations=iterations)) as site:
        engine = site._client.getPhysicsEngineParameters()
    assert engine["numSolverIterations"] == iterations

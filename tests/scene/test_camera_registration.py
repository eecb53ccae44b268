"""A mis-registered head camera: the system places what the camera sees through the pose it
believes, while the renderer uses the true one."""

from dataclasses import replace

import numpy as np
import pytest

from arteleop.ar_features import MODALITIES
from arteleop.errors import ConfigurationError
from arteleop.robot import GRIPPER_FRAME
from arteleop.scene import (
    BASE_FRAME,
    BOWL_FRAME,
    CAMERA_FRAME,
    HeadCameraConfig,
    RemoteSite,
    SiteConfig,
    frame_to_point_cloud,
)
from arteleop.scene.camera_geometry import colocation_errors
from arteleop.teleop import TrialConfig, display_frame, run_trial, trial_operator
from arteleop.transforms import make_transform, transform_points


def test_a_translated_registration_moves_everything_seen_by_that_translation(
    site_config: SiteConfig,
) -> None:
    """Offset t (camera frame): the cloud, the tracked bowl and the display's camera move by
    R_true t in the base frame, exactly; the robot and the bowl themselves do not move."""
    offset_mm = (20.0, -10.0, 5.0)
    camera = replace(site_config.camera, registration_offset_mm=offset_mm)
    with RemoteSite(site_config) as plain, RemoteSite(replace(site_config, camera=camera)) as off:
        truth = plain.camera.T_base_camera
        np.testing.assert_array_equal(off.camera.T_base_camera, truth)
        shift = truth[:3, :3] @ np.array(offset_mm) / 1000
        a = frame_to_point_cloud(plain.capture()).points_m
        b = frame_to_point_cloud(off.capture()).points_m
        assert a.shape == b.shape  # the same pixels: the image is rendered from the true pose
        np.testing.assert_allclose(b - a, np.broadcast_to(shift, a.shape), atol=2e-5)
        np.testing.assert_allclose(
            off.sight_bowl().position_m - plain.sight_bowl().position_m, shift, atol=1e-12
        )
        state = off.observe()
        np.testing.assert_allclose(state.camera.T_base_camera[:3, 3], truth[:3, 3] + shift)
        np.testing.assert_array_equal(state.T_base_bowl, plain.observe().T_base_bowl)
        assert plain.T_cloud_true is None
        np.testing.assert_allclose(off.T_cloud_true, make_transform(np.eye(3), shift), atol=1e-12)


def test_the_display_is_placed_through_the_site_frames(site_config: SiteConfig) -> None:
    """The eye and the cloud at the graph's calibration edge, the bowl reached through it, the
    ghost's gripper at the encoders' forward kinematics, the target at its marker."""
    camera = replace(site_config.camera, registration_offset_deg=(1.0, -2.0, 0.5))
    with RemoteSite(replace(site_config, camera=camera)) as site:
        registered = site.camera.registered.T_base_camera
        graph = site.frames.graph
        assert graph.edge(BASE_FRAME, CAMERA_FRAME).kind == "calibration"
        np.testing.assert_array_equal(graph.T(BASE_FRAME, CAMERA_FRAME), registered)
        state = site.observe()
        track = site.sight_bowl()
        assert graph.path(BASE_FRAME, BOWL_FRAME) == [BASE_FRAME, CAMERA_FRAME, BOWL_FRAME]
        seen_by_camera = transform_points(
            np.linalg.inv(site.camera.T_base_camera), state.bowl_m[None]
        )
        np.testing.assert_allclose(
            track.position_m, transform_points(registered, seen_by_camera)[0], atol=2e-3
        )  # the tracker's estimate is within millimetres of the truth
        frame = display_frame(
            state, track, site.frames, site.config.workspace, MODALITIES["full"], True
        )
        np.testing.assert_array_equal(frame.T_base_camera, registered)
        np.testing.assert_allclose(frame.T_base_gripper, state.link(GRIPPER_FRAME), atol=1e-6)
        np.testing.assert_array_equal(frame.target_m, site.config.workspace.target_m)


def test_colocation_errors_of_a_translated_registration(site_config: SiteConfig) -> None:
    """Offset t in the camera's frame: a point at camera coordinates p is drawn at p - t, so
    the error is |t| in space and the pinhole's f (p - t) / (z - t_z) - f p / z in the image."""
    t = np.array([0.012, -0.004, 0.009])
    camera = replace(site_config.camera, registration_offset_mm=tuple(t * 1000))
    with RemoteSite(replace(site_config, camera=camera)) as site:
        points = np.array([[0.7, -0.3, -0.1], [0.6, 0.0, 0.1]])
        px, m = site.colocation_errors(points)
        p = transform_points(np.linalg.inv(site.camera.T_base_camera), points)
        K = site.camera.intrinsics
        f = np.array([K.fx_px, K.fy_px])
        expected = np.linalg.norm(
            f * (p[:, :2] - t[:2]) / (p[:, 2:] - t[2]) - f * p[:, :2] / p[:, 2:], axis=1
        )
        np.testing.assert_allclose(m, np.linalg.norm(t), rtol=1e-12)
        np.testing.assert_allclose(px, expected, rtol=1e-9)


def test_a_perfect_registration_gives_what_projecting_gives(site_config: SiteConfig) -> None:
    """The site skips the projections when the registration is the camera's true pose: the
    result must be theirs, a non-finite point included."""
    with RemoteSite(site_config) as site:
        assert site.T_cloud_true is None, "premise: the default registration is perfect"
        points = np.array([[0.7, -0.3, -0.1], [0.6, 0.0, 0.1], [np.nan, 0.0, 0.0]])
        camera = site.camera
        expected = colocation_errors(
            camera.T_base_camera, camera.T_base_camera, camera.intrinsics, points
        )
        for ours, theirs in zip(site.colocation_errors(points), expected, strict=True):
            np.testing.assert_array_equal(ours, theirs)


def test_a_trial_records_the_colocation_error_of_its_registration(
    site_config: SiteConfig,
) -> None:
    offset_mm = (15.0, 0.0, 0.0)
    camera = replace(site_config.camera, registration_offset_mm=offset_mm)
    config = TrialConfig(
        modality="full", seed=3, site=replace(site_config, camera=camera), timeout_s=2.0
    )
    with RemoteSite(config.site) as site:
        row = run_trial(trial_operator(site, config), config, site).to_row()
    assert row["colocation_error_m"] == pytest.approx(0.015, rel=1e-9)
    # 15 mm sideways at about 1.3 m from a 57-degree, 640-pixel camera: some 9 px
    assert 6.0 < row["colocation_error_px"] < 12.0


def test_a_rotated_registration_turns_the_view_about_the_camera() -> None:
    config = HeadCameraConfig(registration_offset_deg=(0.0, 2.0, 0.0))
    T = config.T_camera_registered()
    np.testing.assert_allclose(T[:3, 3], 0.0)
    angle = np.degrees(np.arccos((np.trace(T[:3, :3]) - 1) / 2))
    assert angle == pytest.approx(2.0)
    np.testing.assert_allclose(T[:3, 1], [0.0, 1.0, 0.0], atol=1e-15)  # about the camera's y


def test_an_implausible_registration_error_is_refused() -> None:
    with pytest.raises(ConfigurationError) as error:
        HeadCameraConfig(registration_offset_mm=(600.0, 0.0, 0.0))
    assert str(error.value) == (
        "--camera-offset-mm 600.0 0.0 0.0: expected three numbers (mm, camera frame) whose "
        "length is at most 500 mm"
    )
    with pytest.raises(ConfigurationError, match=r"--camera-offset-deg 0.0 90.0 0.0: expected"):
        HeadCameraConfig(registration_offset_deg=(0.0, 90.0, 0.0))


def test_a_registered_pose_replaces_the_offsets(site_config: SiteConfig) -> None:
    with RemoteSite(site_config) as plain:
        truth = plain.camera.T_base_camera.copy()
    T = truth.copy()
    T[:3, 3] += (0.01, 0.02, -0.01)
    pose = tuple(tuple(row) for row in T.tolist())
    camera = replace(site_config.camera, registered_pose=pose)
    with RemoteSite(replace(site_config, camera=camera)) as site:
        np.testing.assert_array_equal(site.camera.registered.T_base_camera, T)
        np.testing.assert_array_equal(site.camera.T_base_camera, truth)
        np.testing.assert_array_equal(site.capture().T_base_camera, T)
    with pytest.raises(ConfigurationError, match=r"registered_pose: expected a rigid 4x4"):
        HeadCameraConfig(registered_pose=pose, registration_offset_mm=(1.0, 0.0, 0.0))
    with pytest.raises(ConfigurationError, match=r"registered_pose: expected a rigid 4x4"):
        HeadCameraConfig(registered_pose=((1.0, 2.0), (3.0,)))

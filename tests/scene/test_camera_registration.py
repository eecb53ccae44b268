"""A mis-registered head camera: the system places what the camera sees through the pose it
believes, while the renderer uses the true one."""

from dataclasses import replace

import numpy as np
import pytest

from arteleop.errors import ConfigurationError
from arteleop.scene import HeadCameraConfig, RemoteSite, SiteConfig, frame_to_point_cloud


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

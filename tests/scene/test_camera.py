from dataclasses import replace

import numpy as np
import pybullet as p
import pytest
from pybullet_utils.bullet_client import BulletClient

from arteleop.errors import ConfigurationError
from arteleop.robot import (
    LEFT_ARM_JOINTS,
    RIGHT_ARM_JOINTS,
    BaxterDescription,
    BaxterDescriptionConfig,
    load_baxter_description,
)
from arteleop.robot.description import HEAD_CAMERA_BLIND_LINKS
from arteleop.scene import (
    CameraGeometry,
    DepthNoiseConfig,
    HeadCameraConfig,
    RemoteSite,
    SiteConfig,
    apply_depth_noise,
    frame_to_point_cloud,
    landmark_problem,
)
from arteleop.transforms import invert_transform, transform_points


def test_kinect_like_field_of_view() -> None:
    h, v = HeadCameraConfig().intrinsics.fov_deg
    assert h == pytest.approx(57.0)
    assert 42.0 < v < 45.0


@pytest.mark.parametrize(("width_px", "height_px"), [(0, 480), (640, 7)])
def test_an_image_too_small_is_refused_with_the_options_to_change(
    width_px: int, height_px: int
) -> None:
    with pytest.raises(ConfigurationError) as error:
        HeadCameraConfig(width_px=width_px, height_px=height_px)
    assert str(error.value) == (
        f"camera image {width_px}x{height_px} px is too small: --width-px and --height-px must "
        "each be at least 8 (the Kinect's is 640x480)"
    )
    assert HeadCameraConfig(width_px=8, height_px=8).intrinsics.width_px == 8


@pytest.mark.parametrize(("width_px", "height_px"), [(640, 480), (320, 240), (160, 120)])
def test_the_landmarks_margin_is_the_same_angle_at_any_resolution(
    width_px: int, height_px: int
) -> None:
    kinect = HeadCameraConfig().intrinsics
    config = HeadCameraConfig(width_px=width_px, height_px=height_px)
    geometry = CameraGeometry(config, np.eye(4))  # the base frame is the optical frame

    def inside_kinects_edge(px: float) -> dict[str, list[float]]:
        # 1 m ahead, on the image's middle row, px inside the left edge of the 640 px image.
        return {"marker": [(px - kinect.cx_px) / kinect.fx_px, 0.0, 1.0]}

    assert landmark_problem(geometry, inside_kinects_edge(15.0)) is None
    problem = landmark_problem(geometry, inside_kinects_edge(5.0))
    assert problem is not None
    assert problem.startswith("The head camera can't see the marker at [-0.")
    assert problem.endswith(
        f"outside the {width_px}x{height_px} image (less {10 * width_px / 640:.3g} px at its edges)"
    )


def test_frame_carries_intrinsics_pose_and_timestamp(site: RemoteSite) -> None:
    site.step(12)
    frame = site.capture()
    assert frame.rgb.shape == (480, 640, 3) and frame.rgb.dtype == np.uint8
    assert frame.depth_m.shape == (480, 640) and frame.depth_m.dtype == np.float32
    assert frame.timestamp_s == pytest.approx(12 / 240)
    expected = site.robot.link_transform("head") @ site.config.camera.T_mount_camera()
    np.testing.assert_allclose(frame.T_base_camera, expected, atol=1e-12)
    assert frame.intrinsics == site.config.camera.intrinsics
    valid = frame.depth_m[frame.depth_m > 0]
    assert valid.min() >= 0.8 and valid.max() <= 4.0


def test_depth_matches_the_scene_geometry(noiseless_site: RemoteSite) -> None:
    site = noiseless_site
    site.step(120)
    frame = site.capture(with_segmentation=True)
    cloud = frame_to_point_cloud(frame)
    seg = frame.segmentation[cloud.pixels[:, 0], cloud.pixels[:, 1]]
    table_z = cloud.points_m[seg == site._bodies["table"], 2]
    assert len(table_z) > 50_000
    # All but the slab's front face (a sliver of pixels) lies on the top face.
    on_top = np.abs(table_z - site.config.workspace.table_top_z_m) < 1e-3
    assert on_top.mean() > 0.99
    assert (
        table_z.min()
        >= site.config.workspace.table_top_z_m - site.config.workspace.table_thickness_m
    )
    # The centre of the bowl's floor projects onto a bowl pixel at the right depth.
    floor = site.observe().bowl_m + [0.0, 0.0, site.config.workspace.bowl.wall_thickness_m]
    pc = transform_points(invert_transform(frame.T_base_camera), floor[None])[0]
    u, v = np.round(frame.intrinsics.project(pc)[0]).astype(int)
    assert frame.segmentation[v, u] == site._bodies["bowl"]
    assert frame.depth_m[v, u] == pytest.approx(pc[2], abs=2e-3)


def test_axial_noise_grows_with_the_square_of_depth() -> None:
    rng = np.random.default_rng(0)
    z = np.repeat(np.array([1.0, 2.0, 3.0], dtype=np.float32), 200_000).reshape(3, -1)
    cfg = DepthNoiseConfig(quantize=False)
    noisy = apply_depth_noise(z, 589.0, cfg, rng)
    sigma = (noisy - z).std(axis=1)
    np.testing.assert_allclose(sigma, 1.425e-3 * np.array([1.0, 4.0, 9.0]), rtol=0.02)


def test_quantisation_lands_on_disparity_steps() -> None:
    cfg = DepthNoiseConfig(enabled=False)
    z = np.linspace(0.8, 4.0, 1000, dtype=np.float32)[None]
    q = apply_depth_noise(z, 589.0, cfg, np.random.default_rng(0)).astype(np.float64)
    steps = cfg.baseline_m * 589.0 / q / cfg.subpixel
    np.testing.assert_allclose(steps, np.round(steps), atol=1e-3)
    # The error is at most half a step, and a step is z^2 * subpixel / (b f).
    assert np.all(np.abs(q - z) <= 0.5 * cfg.quantization_step_m(4.0, 589.0) + 1e-6)
    assert cfg.quantization_step_m(1.0, 589.0) == pytest.approx(0.125 / (0.075 * 589.0))


@pytest.mark.parametrize("enabled", [True, False])
@pytest.mark.parametrize("quantize", [True, False])
def test_the_in_place_noise_is_the_plain_formula_to_the_bit(enabled: bool, quantize: bool) -> None:
    rng = np.random.default_rng(2)
    z = rng.uniform(0.5, 4.5, (48, 64)).astype(np.float32)
    z[rng.random(z.shape) < 0.2] = 0.0
    z[0, :3] = (np.nan, -1.0, 1e-9)
    config = DepthNoiseConfig(enabled=enabled, quantize=quantize)
    # The model's formulas written plainly, as in the docstring of DepthNoiseConfig.
    plain = z.astype(np.float64)
    valid = plain > 0
    if enabled:
        normal = np.random.default_rng(7).standard_normal(plain.shape)
        plain = np.where(valid, plain + normal * config.sigma_m(plain), 0.0)
    if quantize:
        bf = config.baseline_m * 589.0
        disparity = np.round(bf / np.where(valid, plain, 1.0) / config.subpixel) * config.subpixel
        plain = np.where(valid & (disparity > 0), bf / np.maximum(disparity, config.subpixel), 0.0)
    out = apply_depth_noise(z, 589.0, config, np.random.default_rng(7))
    np.testing.assert_array_equal(out, plain.astype(np.float32))


def test_invalid_pixels_stay_invalid() -> None:
    z = np.array([[0.0, 1.0]], dtype=np.float32)
    out = apply_depth_noise(z, 589.0, DepthNoiseConfig(), np.random.default_rng(0))
    assert out[0, 0] == 0.0 and out[0, 1] > 0


def test_same_seed_same_frame(site_config: SiteConfig) -> None:
    def depth(seed: int) -> np.ndarray:
        with RemoteSite(replace(site_config, seed=seed)) as s:
            return s.capture().depth_m

    a, b, c = depth(3), depth(3), depth(4)
    assert np.array_equal(a, b)
    assert not np.array_equal(a, c)


def test_a_frames_noise_depends_on_its_time_not_on_the_frames_before(
    site_config: SiteConfig,
) -> None:
    """Rendering only some frames (the tracker's) gives the frames an every-tick render gives."""

    def depths(render_first: bool) -> tuple[np.ndarray, np.ndarray]:
        with RemoteSite(site_config) as s:
            if render_first:
                s.capture()
            s.step()
            later = s.capture().depth_m
            s.step()
            return later, s.capture().depth_m

    every, every_next = depths(render_first=True)
    some, some_next = depths(render_first=False)
    assert np.array_equal(every, some) and np.array_equal(every_next, some_next)
    assert not np.array_equal(every, every_next)  # fresh noise at another instant


def _links_seen(site: RemoteSite, description: BaxterDescription, n_poses: int = 25) -> set[str]:
    """Links of ``description`` that the site's head camera sees over random right-arm poses.

    The URDF is loaded unmerged into a client of its own: the site's body merges fixed links, so
    its segmentation can't tell the torso from the base.
    """
    cam = site.camera
    client = BulletClient(connection_mode=p.DIRECT)
    try:
        body = client.loadURDF(str(description.urdf_path), useFixedBase=True)
        info = [client.getJointInfo(body, i) for i in range(client.getNumJoints(body))]
        names = {i: row[12].decode() for i, row in enumerate(info)}
        joints = {row[1].decode(): i for i, row in enumerate(info)}
        for name, q in zip(LEFT_ARM_JOINTS, site.robot.left_arm_rad, strict=True):
            client.resetJointState(body, joints[name], q)
        rng = np.random.default_rng(1)
        lim = site.robot.right_arm_limits
        seen: set[str] = set()
        for _ in range(n_poses):
            for name, q in zip(RIGHT_ARM_JOINTS, rng.uniform(lim.lower, lim.upper), strict=True):
                client.resetJointState(body, joints[name], q)
            seg = np.asarray(
                client.getCameraImage(
                    160,
                    120,
                    cam._view_gl,
                    cam._proj_gl,
                    shadow=0,
                    renderer=p.ER_TINY_RENDERER,
                    flags=p.ER_SEGMENTATION_MASK_OBJECT_AND_LINKINDEX,
                )[4]
            ).ravel()
            seg = seg[seg >= 0]
            mine = seg[(seg & ((1 << 24) - 1)) == body]
            seen |= {names.get(int(link), "base") for link in (mine >> 24) - 1}
        return seen
    finally:
        client.disconnect()


def test_hidden_links_are_never_in_the_head_cameras_view(
    site: RemoteSite, description_config: BaxterDescriptionConfig
) -> None:
    """Links the render model hides are ones the camera never sees, and hiding adds nothing."""
    full = load_baxter_description(replace(description_config, hidden_links=()))
    seen_full = _links_seen(site, full)
    assert "right_gripper_base_link" in seen_full
    assert not seen_full & set(HEAD_CAMERA_BLIND_LINKS)
    # PyBullet draws a link's collision shape when it has no visual; the speck prevents that.
    assert not _links_seen(site, site.description) & set(HEAD_CAMERA_BLIND_LINKS)

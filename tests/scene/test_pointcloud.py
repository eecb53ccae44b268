import numpy as np

from arteleop.scene import CameraIntrinsics, RGBDFrame, frame_to_point_cloud
from arteleop.transforms import invert_transform, pose_to_transform, transform_points


def _frame(depth: np.ndarray, T: np.ndarray) -> RGBDFrame:
    h, w = depth.shape
    rgb = np.zeros((h, w, 3), dtype=np.uint8)
    rgb[..., 0] = np.arange(w, dtype=np.uint8)[None, :]
    return RGBDFrame(
        rgb, depth.astype(np.float32), CameraIntrinsics.from_horizontal_fov(w, h, 57.0), T, 0.0
    )


def test_back_projection_round_trip() -> None:
    rng = np.random.default_rng(0)
    depth = rng.uniform(0.8, 4.0, size=(48, 64)).astype(np.float32)
    depth[5, 7] = 0.0
    T = pose_to_transform(
        [0.1, -0.2, 0.9], [0.9, 0.1, -0.3, 0.2] / np.linalg.norm([0.9, 0.1, -0.3, 0.2])
    )
    frame = _frame(depth, T)
    cloud = frame_to_point_cloud(frame)
    assert len(cloud.points_m) == depth.size - 1
    pc = transform_points(invert_transform(T), cloud.points_m)
    uv = frame.intrinsics.project(pc)
    np.testing.assert_allclose(uv[:, ::-1], cloud.pixels, atol=1e-6)
    np.testing.assert_allclose(pc[:, 2], depth[cloud.pixels[:, 0], cloud.pixels[:, 1]], rtol=1e-6)
    assert np.array_equal(cloud.colors[:, 0], cloud.pixels[:, 1].astype(np.uint8))


def test_strided_cloud_is_a_subset_of_the_full_cloud() -> None:
    depth = np.full((48, 64), 2.0, dtype=np.float32)
    frame = _frame(depth, np.eye(4))
    full = frame_to_point_cloud(frame)
    thin = frame_to_point_cloud(frame, stride=4)
    assert len(thin.points_m) == 12 * 16
    index = {tuple(px): i for i, px in enumerate(full.pixels.tolist())}
    rows = [index[tuple(px)] for px in thin.pixels.tolist()]
    np.testing.assert_allclose(thin.points_m, full.points_m[rows], atol=1e-12)


def test_cloud_is_the_grid_back_projection_at_the_valid_pixels_to_the_bit() -> None:
    """The cloud back-projects only the valid pixels; the numbers are those of the whole grid."""
    from arteleop.scene.pointcloud import depth_to_camera_points

    rng = np.random.default_rng(1)
    depth = rng.uniform(0.5, 4.0, size=(96, 128)).astype(np.float32)
    depth[rng.random(depth.shape) < 0.3] = 0.0
    T = pose_to_transform(
        [0.3, 0.1, 1.2], [0.8, -0.2, 0.4, 0.4] / np.linalg.norm([0.8, -0.2, 0.4, 0.4])
    )
    frame = _frame(depth, T)
    for stride in (1, 2, 3):
        thin = depth[::stride, ::stride]
        grid = depth_to_camera_points(thin, frame.intrinsics.strided(stride))
        valid = thin > 0
        cloud = frame_to_point_cloud(frame, stride)
        np.testing.assert_array_equal(cloud.points_m, transform_points(T, grid[valid]))
        np.testing.assert_array_equal(cloud.colors, frame.rgb[::stride, ::stride][valid])
        np.testing.assert_array_equal(cloud.pixels, np.argwhere(valid) * stride)

import numpy as np
import pytest

from arteleop.errors import ConfigurationError
from arteleop.scene import CameraIntrinsics, MeshReconstructor, MeshReconstructorConfig, RGBDFrame


def _frame(depth: np.ndarray) -> RGBDFrame:
    h, w = depth.shape
    K = CameraIntrinsics.from_horizontal_fov(w, h, 57.0)
    return RGBDFrame(np.zeros((h, w, 3), np.uint8), depth.astype(np.float32), K, np.eye(4), 0.0)


def test_small_holes_are_filled_and_large_ones_kept() -> None:
    depth = np.full((60, 80), 1.2, dtype=np.float32)
    depth[10:15, 10:15] = 0.0  # 25 px
    depth[30:50, 40:60] = 0.0  # 400 px
    mr = MeshReconstructor(MeshReconstructorConfig(stride=1, max_hole_px=64))
    filled = mr.fill_holes(depth)
    np.testing.assert_allclose(filled[10:15, 10:15], 1.2, atol=1e-3)
    assert np.all(filled[30:50, 40:60] == 0.0)


def test_triangles_never_join_surfaces_far_apart() -> None:
    h, w = 40, 60
    depth = np.full((h, w), 1.0, dtype=np.float32)
    depth[:, w // 2 :] = 1.5
    mesh = MeshReconstructor(MeshReconstructorConfig(stride=1)).reconstruct(_frame(depth))
    z = mesh.vertices_m[:, 2][mesh.triangles]
    assert np.all(np.ptp(z, axis=1) < 1e-6)
    # Each half is a full grid of (h - 1) * (w / 2 - 1) quads, two triangles each.
    assert len(mesh.triangles) == 2 * 2 * (h - 1) * (w // 2 - 1)
    assert mesh.to_open3d().has_vertex_colors()


def test_averaging_reduces_noise_by_sqrt_n() -> None:
    rng = np.random.default_rng(0)
    mr = MeshReconstructor(MeshReconstructorConfig(average_frames=8))
    for _ in range(8):
        avg = mr.averaged_depth((1.5 + 0.004 * rng.standard_normal((100, 100))).astype(np.float32))
    assert avg.std() == pytest.approx(0.004 / np.sqrt(8), rel=0.1)


def test_averaging_ignores_invalid_samples() -> None:
    mr = MeshReconstructor(MeshReconstructorConfig(average_frames=3))
    mr.averaged_depth(np.array([[1.0, 0.0]], np.float32))
    out = mr.averaged_depth(np.array([[2.0, 3.0]], np.float32))
    np.testing.assert_allclose(out, [[1.5, 3.0]])


def test_bad_config() -> None:
    with pytest.raises(ConfigurationError, match="stride"):
        MeshReconstructorConfig(stride=0)

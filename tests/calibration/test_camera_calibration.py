"""Registering the head camera: ArUco detection against the simulator's ground truth, hand-eye
solvers on exact synthetic data, the robust refinement, and the errors for bad input."""

from dataclasses import replace

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from arteleop.calibration import (
    HAND_EYE_METHODS,
    ArucoMarker,
    CalibrationConfig,
    HandEyeData,
    calibrate_with_table_marker,
    calibration_errors,
    collect_hand_eye,
    detect_marker,
    refine_hand_eye,
    solve_hand_eye,
)
from arteleop.errors import CalibrationError, ConfigurationError
from arteleop.scene import HeadCameraConfig, MarkerBody, RemoteSite
from arteleop.transforms import invert_transform, make_transform, transform_points

BOARD = ArucoMarker(marker_id=3, side_m=0.12, margin_m=0.015)
K = HeadCameraConfig().intrinsics
T_BASE_CAMERA = make_transform(
    Rotation.from_euler("xyz", [-2.3, 0.05, -1.6]).as_matrix(), [0.1, 0, 0.8]
)
T_GRIPPER_BOARD = make_transform(Rotation.random(random_state=1).as_matrix(), [0.0, 0.02, 0.07])


def _synthetic(n: int, spread_rad: float = np.pi, seed: int = 0) -> HandEyeData:
    """Exact sightings of the board for n gripper poses: the relation hand-eye solves."""
    rng = np.random.default_rng(seed)
    grippers = np.array([
        make_transform(
            Rotation.from_rotvec(rng.normal(size=3) * spread_rad).as_matrix(),
            rng.uniform([0.5, -0.5, 0.0], [0.8, 0.0, 0.3]),
        )
        for _ in range(n)
    ])  # fmt: skip
    markers = np.array([invert_transform(T_BASE_CAMERA) @ T @ T_GRIPPER_BOARD for T in grippers])
    corners = np.array([K.project(transform_points(T, BOARD.corners_m)) for T in markers])
    return HandEyeData(grippers, markers, corners, n)


@pytest.mark.parametrize("method", sorted(HAND_EYE_METHODS))
def test_every_solver_recovers_the_camera_from_exact_sightings(method: str) -> None:
    """The eye-to-hand set-up through OpenCV's eye-in-hand and robot-world solvers."""
    result = solve_hand_eye(_synthetic(8), method, BOARD, K)
    errors = calibration_errors(result.T_base_camera, T_BASE_CAMERA, K, np.zeros((1, 3)))
    assert errors.error_mm < 1e-6 and errors.error_deg < 1e-6
    assert result.reprojection_error_px < 1e-6


def test_refinement_ignores_a_mirrored_sighting() -> None:
    """A planar marker seen obliquely can give the mirrored pose; one such sighting ruins the
    closed form, and the robust refinement on the corners does not follow it."""
    exact = _synthetic(10, seed=3)
    markers = exact.T_camera_marker.copy()
    flip = make_transform(Rotation.from_euler("x", 50, degrees=True).as_matrix(), [0, 0, 0])
    markers[4] = markers[4] @ flip  # the pose is wrong, its corners were seen right
    data = replace(exact, T_camera_marker=markers)
    closed = solve_hand_eye(data, "park", BOARD, K)
    refined = refine_hand_eye(data, closed, BOARD, K)
    before = calibration_errors(closed.T_base_camera, T_BASE_CAMERA, K, np.zeros((1, 3)))
    after = calibration_errors(refined.T_base_camera, T_BASE_CAMERA, K, np.zeros((1, 3)))
    assert before.error_mm > 10
    assert after.error_mm < 0.01 and after.error_deg < 1e-3
    assert refined.method == "park + refined"


def test_too_few_or_too_similar_poses_are_refused_with_counts() -> None:
    data = _synthetic(2)
    with pytest.raises(CalibrationError) as error:
        solve_hand_eye(replace(data, attempts=9), "tsai", BOARD, K)
    assert str(error.value) == (
        "2 usable poses (the board found in 2 of 9 tried); hand-eye calibration needs at least 3."
        " Aim the board at the camera (CalibrationConfig.board_region_m, board_tilt_rad) or "
        "allow more attempts."
    )
    similar = r"6 usable poses are too similar: the gripper's rotations differ by at most 0\.9 deg"
    with pytest.raises(CalibrationError, match=similar):
        solve_hand_eye(_synthetic(6, spread_rad=0.005), "tsai", BOARD, K)
    with pytest.raises(ConfigurationError, match=r"--method kalman: not a hand-eye method"):
        solve_hand_eye(data, "kalman", BOARD, K)
    with pytest.raises(ConfigurationError, match=r"--poses 2: hand-eye calibration needs at "):
        CalibrationConfig(poses=2)


def test_markers_are_checked() -> None:
    with pytest.raises(ConfigurationError, match=r"marker_id=60 is not in DICT_4X4_50, whose ids"):
        ArucoMarker(marker_id=60)
    with pytest.raises(ConfigurationError, match=r"'DICT_9X9' is not an OpenCV ArUco dictionary"):
        ArucoMarker(dictionary="DICT_9X9")


def test_a_marker_on_the_table_is_found_where_it_lies(noiseless_site: RemoteSite) -> None:
    """Detection against simulator ground truth: the corners within a pixel, without bias (the
    renderer's pixel grid and the intrinsics agree), and the pose within millimetres."""
    site = noiseless_site
    marker = ArucoMarker(marker_id=7, side_m=0.15)
    body = MarkerBody(site.render_world.client, marker)
    T_camera_base = invert_transform(site.camera.T_base_camera)
    offsets = []
    for x, y, turn in ((0.6, -0.25, 0.3), (0.75, 0.0, -1.0), (0.55, -0.05, 2.0)):
        T_base_marker = make_transform(
            Rotation.from_euler("z", turn).as_matrix(),
            site.config.workspace.on_table((x, y)) + [0.0, 0.0, 0.001],
        )
        body.place(T_base_marker)
        frame = site.capture()
        seen = detect_marker(frame.rgb, frame.intrinsics, marker)
        assert seen is not None
        truth = T_camera_base @ T_base_marker
        expected = K.project(transform_points(truth, marker.corners_m))
        offsets.append(seen.corners_px - expected)
        assert np.linalg.norm(seen.T_camera_marker[:3, 3] - truth[:3, 3]) < 0.015
    offsets = np.concatenate(offsets)
    assert np.abs(offsets).max() < 1.0
    assert np.abs(offsets.mean(axis=0)).max() < 0.15  # no half-pixel shift
    body.remove()
    assert detect_marker(site.capture().rgb, K, marker) is None


def test_both_calibrations_find_the_camera_in_simulation(site: RemoteSite) -> None:
    """On the simulator's true pose (hidden from the solvers), one seed: hand-eye with 10 poses
    within 1 cm and 0.5 deg after refinement, the ghost within 3 px; the helper within 2 cm.
    The issue's target (5 mm, 0.5 deg with 10 poses) is a median over seeds: see
    benchmarks/bench_calibration.py."""
    config = CalibrationConfig(poses=10, seed=0, table_placements=3)
    truth = site.camera.T_base_camera.copy()
    helper = calibrate_with_table_marker(site, config)
    data = collect_hand_eye(site, config)
    assert len(data.T_base_gripper) == 10
    best = min(
        (solve_hand_eye(data, m, config.board, K) for m in HAND_EYE_METHODS),
        key=lambda r: r.reprojection_error_px,
    )
    refined = refine_hand_eye(data, best, config.board, K)
    positions = data.T_base_gripper[:, :3, 3]
    e = calibration_errors(refined.T_base_camera, truth, K, positions)
    assert e.error_mm < 10.0 and e.error_deg < 0.5
    assert e.colocation_px < 3.0
    h = calibration_errors(helper.T_base_camera, truth, K, positions)
    assert h.error_mm < 20.0 and h.error_deg < 0.8
    assert helper.poses == 3 and helper.covariance is not None
    np.testing.assert_array_equal(site.camera.T_base_camera, truth)


def test_a_marker_never_seen_says_so(site: RemoteSite) -> None:
    tiny = ArucoMarker(marker_id=7, side_m=0.01, margin_m=0.002)
    config = CalibrationConfig(table_marker=tiny, table_placements=2)
    with pytest.raises(CalibrationError) as error:
        calibrate_with_table_marker(site, config)
    assert str(error.value).startswith(
        "The table marker was never seen in 2 placements: 0 usable sightings, at least 1 needed."
    )


def test_an_unknown_hand_eye_method_is_refused_before_anything_runs() -> None:
    from arteleop.calibration import calibrate_camera

    with pytest.raises(CalibrationError) as err:
        calibrate_camera(None, CalibrationConfig(), "tsia")  # type: ignore[arg-type]
    assert str(err.value) == (
        "hand-eye method 'tsia': expected best or one of tsai, park, horaud, andreff, "
        "daniilidis, shah, li"
    )

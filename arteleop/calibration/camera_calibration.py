"""Registering the head camera to the robot: where the optical frame is in the base frame.

Two procedures, each given only the camera's images, its intrinsics and the robot's joint
readings (the simulator's true camera pose is used only to score the result, by the caller):

- **helper-based**: an ArUco marker lies on the table at a known place; each sighting gives
  ``T_base_camera = T_base_marker T_camera_marker^-1``, and the sightings, at several places,
  are averaged into one estimate with its covariance;
- **hand-eye**: the gripper holds a marker board at an unknown offset and shows it to the
  camera in N poses. The camera is fixed to the base, so ``T_camera_marker_i = T_camera_base
  T_base_gripper_i T_gripper_marker`` with two unknowns, solved by OpenCV's hand-eye methods
  (AX = XB) and robot-world hand-eye methods (AX = ZB).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import cv2
import numpy as np
import pinocchio as pin
from numpy.typing import NDArray
from scipy.optimize import least_squares
from scipy.spatial.transform import Rotation

from arteleop.calibration.aruco import ArucoMarker, detect_marker
from arteleop.errors import CalibrationError, ConfigurationError
from arteleop.frames.uncertain_transform import UncertainTransform, mean_transform
from arteleop.robot import GRIPPER_FRAME, RIGHT_ARM_JOINTS
from arteleop.scene.camera_config import CameraIntrinsics
from arteleop.scene.camera_geometry import colocation_errors
from arteleop.scene.marker_body import MarkerBody
from arteleop.scene.site import RemoteSite
from arteleop.transforms import invert_transform, make_transform, transform_points

HAND_EYE_METHODS: dict[str, tuple[str, int]] = {
    "tsai": ("hand-eye", cv2.CALIB_HAND_EYE_TSAI),
    "park": ("hand-eye", cv2.CALIB_HAND_EYE_PARK),
    "horaud": ("hand-eye", cv2.CALIB_HAND_EYE_HORAUD),
    "andreff": ("hand-eye", cv2.CALIB_HAND_EYE_ANDREFF),
    "daniilidis": ("hand-eye", cv2.CALIB_HAND_EYE_DANIILIDIS),
    "shah": ("robot-world", cv2.CALIB_ROBOT_WORLD_HAND_EYE_SHAH),
    "li": ("robot-world", cv2.CALIB_ROBOT_WORLD_HAND_EYE_LI),
}
"""OpenCV's solvers by name: Tsai-Lenz 1989, Park-Martin 1994, Horaud-Dornaika 1995, Andreff
et al. 1999, Daniilidis 1999 (AX = XB); Shah 2013, Li et al. 2010 (AX = ZB)."""

MIN_POSES = 3
MIN_ROTATION_SPREAD_DEG = 5.0
"""Hand-eye needs rotations about at least two different axes; poses whose rotations all lie
within this angle of each other leave the translation undetermined."""


def _board_mount() -> NDArray[np.float64]:
    # The board hangs below the closed fingers, its printed face towards the gripper's -x:
    # x_marker = y_gripper, y_marker = -z_gripper, z_marker = -x_gripper.
    R = np.column_stack([[0.0, 1.0, 0.0], [0.0, 0.0, -1.0], [-1.0, 0.0, 0.0]])
    return make_transform(R, [0.0, 0.0, 0.075])


@dataclass(frozen=True)
class CalibrationConfig:
    """How the calibrations are run.

    Attributes:
        poses: Hand-eye: usable poses to collect (the marker found in each).
        attempts_per_pose: Hand-eye: poses tried per usable pose before giving up.
        board: The marker the gripper holds; a side of 12 cm keeps its corners' sub-pixel
            accuracy at the distances the arm reaches.
        T_gripper_board: Where the gripper holds it (the solver does not know it).
        board_tilt_rad: SD of the board's random tilt away from facing the camera: the spread
            of rotations hand-eye needs (at 0.15 rad the closed-form methods erred by 1-25 cm
            on 10 poses, at 0.3 by 1-6 cm), kept small enough that the board stays readable
            (found in 10 of 10-13 poses).
        board_region_m: Hand-eye: (min, max) of the board's position (x, y in the base frame,
            height above the table top), drawn uniformly.
        table_marker: The marker of the helper-based calibration.
        table_placements: Helper-based: places on the table where it is put, one sighting each.
        seed: Seeds the poses and placements.
    """

    poses: int = 10
    attempts_per_pose: int = 4
    board: ArucoMarker = field(
        default_factory=lambda: ArucoMarker(marker_id=3, side_m=0.12, margin_m=0.015)
    )
    T_gripper_board: NDArray[np.float64] = field(default_factory=_board_mount, compare=False)
    board_tilt_rad: float = 0.3
    board_region_m: tuple[tuple[float, float, float], tuple[float, float, float]] = (
        (0.5, -0.5, 0.12),
        (0.8, 0.0, 0.35),
    )
    table_marker: ArucoMarker = field(
        default_factory=lambda: ArucoMarker(marker_id=7, side_m=0.15, margin_m=0.03)
    )
    table_placements: int = 5
    seed: int = 0

    def __post_init__(self) -> None:
        if self.poses < MIN_POSES:
            raise ConfigurationError(
                f"--poses {self.poses}: hand-eye calibration needs at least {MIN_POSES} poses"
            )
        if self.attempts_per_pose < 1 or self.table_placements < 1:
            raise ConfigurationError(
                "CalibrationConfig.attempts_per_pose and table_placements must be >= 1; got "
                f"{self.attempts_per_pose} and {self.table_placements}"
            )


@dataclass(frozen=True)
class CameraCalibration:
    """One estimate of the head camera's pose.

    Attributes:
        method: ``helper`` or a key of :data:`HAND_EYE_METHODS`.
        T_base_camera: The estimate (4x4, m), optical frame in the base frame.
        covariance: Its 6x6 covariance (left perturbation, m and rad), where the method gives
            one (the helper's mean of sightings); None otherwise.
        poses: Sightings used.
        reprojection_error_px: RMS distance between the detected marker corners and those
            predicted through the estimate (the helper: through each sighting's own pose).
    """

    method: str
    T_base_camera: NDArray[np.float64]
    covariance: NDArray[np.float64] | None
    poses: int
    reprojection_error_px: float

    @property
    def transform(self) -> UncertainTransform:
        return UncertainTransform(self.T_base_camera, self.covariance)


@dataclass(frozen=True)
class CalibrationErrors:
    """An estimate against the true camera pose.

    Attributes:
        error_mm, error_deg: Translation and rotation of ``T_true^-1 T_estimate``.
        colocation_px, colocation_mm: Median over the given gripper positions of how far the
            ghost's gripper, drawn through the estimate, lands from the real gripper: in the
            image (px) and in space (mm).
    """

    error_mm: float
    error_deg: float
    colocation_px: float
    colocation_mm: float


@dataclass(frozen=True)
class HandEyeData:
    """The sightings of hand-eye calibration: per usable pose, the gripper's pose from the
    robot's joint readings, the board's pose from the image, and its detected corners."""

    T_base_gripper: NDArray[np.float64]
    T_camera_marker: NDArray[np.float64]
    corners_px: NDArray[np.float64]
    attempts: int


def calibrate_with_table_marker(site: RemoteSite, config: CalibrationConfig) -> CameraCalibration:
    """Helper-based calibration: the table marker at ``config.table_placements`` known places
    on the table, seen once each, the estimates averaged."""
    ws = site.config.workspace
    rng = np.random.default_rng((config.seed, 1))
    lo, hi = ws.table_bounds_xy_m()
    body = MarkerBody(site.render_world.client, config.table_marker)
    estimates, errors = [], []
    try:
        for _ in range(config.table_placements):
            xy = rng.uniform(lo + 0.15, hi - 0.15)
            turn = Rotation.from_euler("z", rng.uniform(-np.pi, np.pi)).as_matrix()
            T_base_marker = make_transform(turn, ws.on_table(xy) + [0.0, 0.0, 0.001])
            body.place(T_base_marker)
            frame = site.capture()
            seen = detect_marker(frame.rgb, frame.intrinsics, config.table_marker)
            if seen is None:
                continue
            estimates.append(T_base_marker @ invert_transform(seen.T_camera_marker))
            errors.append(seen.reprojection_error_px)
    finally:
        body.remove()
    if not estimates:
        raise CalibrationError(
            f"The table marker was never seen in {config.table_placements} placements: 0 usable "
            "sightings, at least 1 needed. Check that the camera sees the table "
            "(HeadCameraConfig) and that the marker is large enough (table_marker.side_m)."
        )
    mean = mean_transform(estimates)
    return CameraCalibration(
        "helper",
        mean.T,
        mean.covariance,
        len(estimates),
        float(np.sqrt(np.mean(np.square(errors)))),
    )


def collect_hand_eye(site: RemoteSite, config: CalibrationConfig) -> HandEyeData:
    """Show the held board to the camera in ``config.poses`` usable poses: each pose faces the
    board towards the camera, tilted at random; the arm is placed there with PyBullet's IK (a
    teleport: the physics is not stepped), the frame rendered and the board looked for."""
    rng = np.random.default_rng((config.seed, 2))
    ws = site.config.workspace
    (x0, y0, h0), (x1, y1, h1) = config.board_region_m
    eye = site.camera.T_base_camera[:3, 3]  # aiming the board only, as a person would by eye
    T_board_gripper = invert_transform(config.T_gripper_board)
    body = MarkerBody(site.render_world.client, config.board)
    grippers, markers, corners = [], [], []
    attempts = 0
    try:
        while len(grippers) < config.poses and attempts < config.poses * config.attempts_per_pose:
            attempts += 1
            position = rng.uniform((x0, y0, ws.table_top_z_m + h0), (x1, y1, ws.table_top_z_m + h1))
            facing = _facing(eye - position)
            tilt = Rotation.from_rotvec(rng.normal(size=3) * config.board_tilt_rad).as_matrix()
            target = make_transform(facing @ tilt, position) @ T_board_gripper
            for _ in range(8):  # PyBullet's IK improves from its own answer
                q = site.robot.pybullet_ik(target)
                site.robot.set_joint_positions(dict(zip(RIGHT_ARM_JOINTS, q, strict=True)))
            T_base_gripper = site.robot.link_transform(GRIPPER_FRAME)
            body.place(T_base_gripper @ config.T_gripper_board)
            frame = site.capture()
            seen = detect_marker(frame.rgb, frame.intrinsics, config.board)
            if seen is not None:
                grippers.append(T_base_gripper)
                markers.append(seen.T_camera_marker)
                corners.append(seen.corners_px)
    finally:
        body.remove()
    data = HandEyeData(
        np.array(grippers).reshape(-1, 4, 4),
        np.array(markers).reshape(-1, 4, 4),
        np.array(corners).reshape(-1, 4, 2),
        attempts,
    )
    check_hand_eye_data(data)
    return data


def check_hand_eye_data(data: HandEyeData) -> None:
    """Raise :class:`CalibrationError` unless the sightings can determine the transform."""
    n = len(data.T_base_gripper)
    if n < MIN_POSES:
        raise CalibrationError(
            f"{n} usable poses (the board found in {n} of {data.attempts} tried); hand-eye "
            f"calibration needs at least {MIN_POSES}. Aim the board at the camera "
            "(CalibrationConfig.board_region_m, board_tilt_rad) or allow more attempts."
        )
    rotations = Rotation.from_matrix(data.T_base_gripper[:, :3, :3])
    spread = float(np.degrees((rotations[0].inv() * rotations).magnitude().max()))
    if spread < MIN_ROTATION_SPREAD_DEG:
        raise CalibrationError(
            f"The {n} usable poses are too similar: the gripper's rotations differ by at most "
            f"{spread:.1f} deg, and hand-eye calibration needs at least "
            f"{MIN_ROTATION_SPREAD_DEG:.0f} deg. Tilt the board more "
            "(CalibrationConfig.board_tilt_rad)."
        )


def solve_hand_eye(
    data: HandEyeData, method: str, board: ArucoMarker, intrinsics: CameraIntrinsics
) -> CameraCalibration:
    """``T_base_camera`` from the sightings with one of OpenCV's solvers (see
    :data:`HAND_EYE_METHODS`)."""
    if method not in HAND_EYE_METHODS:
        raise ConfigurationError(
            f"--method {method}: not a hand-eye method; choose from {sorted(HAND_EYE_METHODS)}"
        )
    check_hand_eye_data(data)
    if not hasattr(cv2, "calibrateHandEye"):
        raise CalibrationError(
            f"OpenCV {cv2.__version__} has no calibrateHandEye in Python (the 5.0.0 wheels lost "
            "it, opencv/opencv#29565). Install a 4.x: pip install 'opencv-python-headless<5'."
        )
    kind, flag = HAND_EYE_METHODS[method]
    T_camera_marker = data.T_camera_marker
    if kind == "hand-eye":
        # Eye-to-hand through the eye-in-hand solver: give it T_gripper_base as the "gripper to
        # base" poses, and the "camera to gripper" it returns is T_base_camera.
        T_gripper_base = np.linalg.inv(data.T_base_gripper)
        R, t = cv2.calibrateHandEye(
            T_gripper_base[:, :3, :3], T_gripper_base[:, :3, 3],
            T_camera_marker[:, :3, :3], T_camera_marker[:, :3, 3], method=flag,
        )  # fmt: skip
        T_base_camera = make_transform(R, t.ravel())
        T_camera_base = invert_transform(T_base_camera)
        T_gripper_marker = _board_mounting(data, T_base_camera)  # for the reprojection check
    else:
        # T_camera_marker = T_camera_base T_base_gripper T_gripper_marker is OpenCV's
        # T_cam_world = T_cam_gripper T_gripper_base T_base_world with the robot's base in the
        # role of its gripper and our gripper in the role of its base.
        R_bw, t_bw, R_gc, t_gc = cv2.calibrateRobotWorldHandEye(
            T_camera_marker[:, :3, :3], T_camera_marker[:, :3, 3],
            data.T_base_gripper[:, :3, :3], data.T_base_gripper[:, :3, 3], method=flag,
        )  # fmt: skip
        T_camera_base = make_transform(R_gc, t_gc.ravel())
        T_gripper_marker = invert_transform(make_transform(R_bw, t_bw.ravel()))
        T_base_camera = invert_transform(T_camera_base)
    residuals = _corner_residuals(data, T_camera_base, T_gripper_marker, board, intrinsics)
    return CameraCalibration(
        method, T_base_camera, None, len(data.T_base_gripper), _rms_px(residuals)
    )


def refine_hand_eye(
    data: HandEyeData,
    initial: CameraCalibration,
    board: ArucoMarker,
    intrinsics: CameraIntrinsics,
    outlier_px: float = 2.0,
) -> CameraCalibration:
    """Refine a closed-form hand-eye estimate by minimising the corners' reprojection error over
    both unknowns (``T_camera_base`` and the board's mounting), with scipy's ``least_squares``.

    The closed-form methods weigh each sighting's estimated pose, whose rotation about the
    marker plane is its least certain part, and a marker seen obliquely sometimes gives the
    mirrored pose (a planar target's two-fold ambiguity). The refinement uses the detected
    corners themselves, and a robust (Cauchy) loss of scale ``outlier_px`` keeps such a
    sighting from pulling the answer. Its covariance is the Gauss-Newton one, scaled by the
    residuals' variance.
    """
    T_camera_base = invert_transform(initial.T_base_camera)
    T_gripper_marker = _board_mounting(data, initial.T_base_camera)

    def poses(x: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        return (
            pin.exp6(x[:6]).homogeneous @ T_camera_base,
            pin.exp6(x[6:]).homogeneous @ T_gripper_marker,
        )

    def residuals(x: NDArray[np.float64]) -> NDArray[np.float64]:
        return _corner_residuals(data, *poses(x), board, intrinsics).ravel()

    fit = least_squares(residuals, np.zeros(12), loss="cauchy", f_scale=outlier_px)
    T_cb, _ = poses(fit.x)
    # Gauss-Newton covariance of the camera's left perturbation of T_camera_base; moved onto
    # T_base_camera's left perturbation by the inverse's adjoint.
    dof = max(len(fit.fun) - 12, 1)
    sigma2 = float(np.median(fit.fun**2)) / 0.4549 * len(fit.fun) / dof  # robust scale
    try:
        cov_x = np.linalg.inv(fit.jac.T @ fit.jac)[:6, :6] * sigma2
    except np.linalg.LinAlgError:
        cov_x = None
    T_base_camera = invert_transform(T_cb)
    covariance = None
    if cov_x is not None:
        Ad = pin.SE3(T_base_camera).action
        covariance = Ad @ cov_x @ Ad.T
        covariance = (covariance + covariance.T) / 2
    rms = _rms_px(fit.fun.reshape(-1, 2))  # the residuals at the solution
    return CameraCalibration(
        f"{initial.method} + refined", T_base_camera, covariance, len(data.T_base_gripper), rms
    )


@dataclass(frozen=True)
class CalibrationRun:
    """Both calibrations of one site, as ``arteleop calibrate`` runs them.

    Attributes:
        helper: The table marker's estimate.
        data: The hand-eye sightings.
        closed_form: Every OpenCV hand-eye solver's estimate, in :data:`HAND_EYE_METHODS`'
            order.
        refined: The chosen closed form refined on the marker's corners.
    """

    helper: CameraCalibration
    data: HandEyeData
    closed_form: tuple[CameraCalibration, ...]
    refined: CameraCalibration


def calibrate_camera(
    site: RemoteSite, config: CalibrationConfig, method: str = "best"
) -> CalibrationRun:
    """The helper-based and the hand-eye calibration of ``site``'s head camera; the refinement
    starts from the closed form ``method`` names, or with ``"best"`` from the one with the
    lowest reprojection error (which needs no ground truth)."""
    if method != "best" and method not in HAND_EYE_METHODS:
        raise CalibrationError(
            f"hand-eye method {method!r}: expected best or one of {', '.join(HAND_EYE_METHODS)}"
        )
    helper = calibrate_with_table_marker(site, config)
    data = collect_hand_eye(site, config)
    K = site.camera.intrinsics
    closed = tuple(solve_hand_eye(data, m, config.board, K) for m in HAND_EYE_METHODS)
    if method == "best":
        start = min(closed, key=lambda r: r.reprojection_error_px)
    else:
        start = next(r for r in closed if r.method == method)
    return CalibrationRun(helper, data, closed, refine_hand_eye(data, start, config.board, K))


def calibration_errors(
    T_base_camera: NDArray[np.float64],
    T_base_camera_true: NDArray[np.float64],
    intrinsics: CameraIntrinsics,
    gripper_positions_m: Sequence[NDArray[np.float64]] | NDArray[np.float64],
) -> CalibrationErrors:
    """Score an estimate against the true pose, and the co-location error it gives the ghost at
    the given gripper positions (base frame, m)."""
    error = invert_transform(T_base_camera_true) @ T_base_camera
    angle = Rotation.from_matrix(error[:3, :3]).magnitude()
    px, m = colocation_errors(T_base_camera_true, T_base_camera, intrinsics, gripper_positions_m)
    return CalibrationErrors(
        float(np.linalg.norm(error[:3, 3]) * 1000),
        float(np.degrees(angle)),
        float(np.median(px)),
        float(np.median(m) * 1000),
    )


def _board_mounting(data: HandEyeData, T_base_camera: NDArray[np.float64]) -> NDArray[np.float64]:
    """``T_gripper_marker`` given the camera's pose: the mean over the sightings."""
    return mean_transform(
        [invert_transform(Tg) @ T_base_camera @ Tm
         for Tg, Tm in zip(data.T_base_gripper, data.T_camera_marker, strict=True)]
    ).T  # fmt: skip


def _corner_residuals(
    data: HandEyeData,
    T_camera_base: NDArray[np.float64],
    T_gripper_marker: NDArray[np.float64],
    board: ArucoMarker,
    intrinsics: CameraIntrinsics,
) -> NDArray[np.float64]:
    """(N * 4, 2) corners predicted through the two transforms minus those detected (px)."""
    predicted = [
        intrinsics.project(transform_points(T_camera_base @ Tg @ T_gripper_marker, board.corners_m))
        for Tg in data.T_base_gripper
    ]
    return np.concatenate(predicted) - data.corners_px.reshape(-1, 2)


def _rms_px(residuals: NDArray[np.float64]) -> float:
    """RMS length of (N, 2) pixel residuals."""
    return float(np.sqrt(np.mean(np.sum(residuals**2, axis=1))))


def _facing(towards: NDArray[np.float64]) -> NDArray[np.float64]:
    """A rotation whose z points along ``towards`` and whose x is horizontal."""
    z = towards / np.linalg.norm(towards)
    x = np.cross([0.0, 0.0, 1.0], z)
    x /= np.linalg.norm(x)
    return np.column_stack([x, np.cross(z, x), z])

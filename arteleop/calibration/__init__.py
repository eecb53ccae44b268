"""Registering the head camera to the robot: ArUco markers found with OpenCV, helper-based
calibration (a marker on the table) and hand-eye calibration (a board in the gripper)."""

from arteleop.calibration.aruco import ArucoMarker, MarkerObservation, detect_marker
from arteleop.calibration.camera_calibration import (
    HAND_EYE_METHODS,
    CalibrationConfig,
    CalibrationErrors,
    CalibrationRun,
    CameraCalibration,
    HandEyeData,
    calibrate_camera,
    calibrate_with_table_marker,
    calibration_errors,
    check_hand_eye_data,
    collect_hand_eye,
    refine_hand_eye,
    solve_hand_eye,
)

__all__ = [
    "HAND_EYE_METHODS",
    "ArucoMarker",
    "CalibrationConfig",
    "CalibrationErrors",
    "CalibrationRun",
    "CameraCalibration",
    "HandEyeData",
    "MarkerObservation",
    "calibrate_camera",
    "calibrate_with_table_marker",
    "calibration_errors",
    "check_hand_eye_data",
    "collect_hand_eye",
    "detect_marker",
    "refine_hand_eye",
    "solve_hand_eye",
]

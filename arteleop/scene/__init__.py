"""The remote site: workspace, bowl, head RGB-D camera, point clouds, depth meshes, tracking."""

# First: it loads PyBullet without the banner PyBullet prints on import.
from arteleop.robot import native_output  # noqa: F401

# isort: split
from arteleop.scene.aruco import ArucoMarker, MarkerBody, MarkerObservation, detect_marker
from arteleop.scene.bowl import (
    GRASP_DEPTH_M,
    BowlSpec,
    CollisionBox,
    bowl_collision_boxes,
    bowl_mesh,
)
from arteleop.scene.bowl_sight import BowlSight, BowlSightConfig
from arteleop.scene.bowl_tracking import BowlTrack, BowlTracker, BowlTrackerConfig
from arteleop.scene.camera import HeadCamera, RGBDFrame
from arteleop.scene.camera_calibration import (
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
from arteleop.scene.camera_config import CameraIntrinsics, HeadCameraConfig
from arteleop.scene.camera_geometry import CameraGeometry
from arteleop.scene.depth_mesh import DepthMesh, MeshReconstructor, MeshReconstructorConfig
from arteleop.scene.depth_noise import DepthNoiseConfig, apply_depth_noise
from arteleop.scene.pointcloud import PointCloud, depth_to_camera_points, frame_to_point_cloud
from arteleop.scene.robot_frames import RobotFrames
from arteleop.scene.site import RemoteSite, SiteConfig, reach_problem
from arteleop.scene.site_frames import (
    BASE_FRAME,
    BOWL_FRAME,
    CAMERA_FRAME,
    START_MARKER_FRAME,
    TABLE_FRAME,
    TARGET_MARKER_FRAME,
    SiteFrames,
)
from arteleop.scene.site_state import SiteState
from arteleop.scene.snapshot import SceneSnapshot, write_snapshot
from arteleop.scene.transform_graph import Edge, EdgeKind, TransformGraph
from arteleop.scene.uncertain_transform import (
    UncertainTransform,
    fuse,
    left_error,
    mean_transform,
)
from arteleop.scene.workspace import Box, Workspace

__all__ = [
    "BASE_FRAME",
    "BOWL_FRAME",
    "CAMERA_FRAME",
    "GRASP_DEPTH_M",
    "HAND_EYE_METHODS",
    "START_MARKER_FRAME",
    "TABLE_FRAME",
    "TARGET_MARKER_FRAME",
    "ArucoMarker",
    "BowlSight",
    "BowlSightConfig",
    "BowlSpec",
    "BowlTrack",
    "BowlTracker",
    "BowlTrackerConfig",
    "Box",
    "CalibrationConfig",
    "CalibrationErrors",
    "CalibrationRun",
    "CameraCalibration",
    "CameraGeometry",
    "CameraIntrinsics",
    "CollisionBox",
    "DepthMesh",
    "DepthNoiseConfig",
    "Edge",
    "EdgeKind",
    "HandEyeData",
    "HeadCamera",
    "HeadCameraConfig",
    "MarkerBody",
    "MarkerObservation",
    "MeshReconstructor",
    "MeshReconstructorConfig",
    "PointCloud",
    "RGBDFrame",
    "RemoteSite",
    "RobotFrames",
    "SceneSnapshot",
    "SiteConfig",
    "SiteFrames",
    "SiteState",
    "TransformGraph",
    "UncertainTransform",
    "Workspace",
    "apply_depth_noise",
    "bowl_collision_boxes",
    "bowl_mesh",
    "calibrate_camera",
    "calibrate_with_table_marker",
    "calibration_errors",
    "check_hand_eye_data",
    "collect_hand_eye",
    "depth_to_camera_points",
    "detect_marker",
    "frame_to_point_cloud",
    "fuse",
    "left_error",
    "mean_transform",
    "reach_problem",
    "refine_hand_eye",
    "solve_hand_eye",
    "write_snapshot",
]

"""The remote site: workspace, bowl, head RGB-D camera, point clouds, depth meshes, tracking,
and the site's frames.

The transform graph and its transforms are in :mod:`arteleop.frames`, the camera's calibration
and the ArUco markers in :mod:`arteleop.calibration`.
"""

# First: it loads PyBullet without the banner PyBullet prints on import.
from arteleop.robot import native_output  # noqa: F401

# isort: split
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
from arteleop.scene.camera_config import CameraIntrinsics, HeadCameraConfig
from arteleop.scene.camera_geometry import CameraGeometry, landmark_problem
from arteleop.scene.depth_mesh import DepthMesh, MeshReconstructor, MeshReconstructorConfig
from arteleop.scene.depth_noise import DepthNoiseConfig, apply_depth_noise
from arteleop.scene.mark_sight import MarksSight, start_line_m, target_line_m
from arteleop.scene.marker_body import MarkerBody, PrintedSquare
from arteleop.scene.pointcloud import PointCloud, depth_to_camera_points, frame_to_point_cloud
from arteleop.scene.site import RemoteSite
from arteleop.scene.site_checks import reach_problem
from arteleop.scene.site_config import SiteConfig
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
from arteleop.scene.workspace import Box, Workspace

__all__ = [
    "BASE_FRAME",
    "BOWL_FRAME",
    "CAMERA_FRAME",
    "GRASP_DEPTH_M",
    "START_MARKER_FRAME",
    "TABLE_FRAME",
    "TARGET_MARKER_FRAME",
    "BowlSight",
    "BowlSightConfig",
    "BowlSpec",
    "BowlTrack",
    "BowlTracker",
    "BowlTrackerConfig",
    "Box",
    "CameraGeometry",
    "CameraIntrinsics",
    "CollisionBox",
    "DepthMesh",
    "DepthNoiseConfig",
    "HeadCamera",
    "HeadCameraConfig",
    "MarkerBody",
    "MarksSight",
    "MeshReconstructor",
    "MeshReconstructorConfig",
    "PointCloud",
    "PrintedSquare",
    "RGBDFrame",
    "RemoteSite",
    "SceneSnapshot",
    "SiteConfig",
    "SiteFrames",
    "SiteState",
    "Workspace",
    "apply_depth_noise",
    "bowl_collision_boxes",
    "bowl_mesh",
    "depth_to_camera_points",
    "frame_to_point_cloud",
    "landmark_problem",
    "reach_problem",
    "start_line_m",
    "target_line_m",
    "write_snapshot",
]

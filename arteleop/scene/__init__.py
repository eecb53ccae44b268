"""The remote site: workspace, bowl, head RGB-D camera, point clouds, depth meshes, tracking."""

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
from arteleop.scene.camera_geometry import CameraGeometry
from arteleop.scene.depth_mesh import DepthMesh, MeshReconstructor, MeshReconstructorConfig
from arteleop.scene.depth_noise import DepthNoiseConfig, apply_depth_noise
from arteleop.scene.pointcloud import PointCloud, depth_to_camera_points, frame_to_point_cloud
from arteleop.scene.robot_frames import RobotFrames
from arteleop.scene.site import RemoteSite, SiteConfig, reach_problem
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
    "GRASP_DEPTH_M",
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
    "Edge",
    "EdgeKind",
    "HeadCamera",
    "HeadCameraConfig",
    "MeshReconstructor",
    "MeshReconstructorConfig",
    "PointCloud",
    "RGBDFrame",
    "RemoteSite",
    "RobotFrames",
    "SceneSnapshot",
    "SiteConfig",
    "SiteState",
    "TransformGraph",
    "UncertainTransform",
    "Workspace",
    "apply_depth_noise",
    "bowl_collision_boxes",
    "bowl_mesh",
    "depth_to_camera_points",
    "frame_to_point_cloud",
    "fuse",
    "left_error",
    "mean_transform",
    "reach_problem",
    "write_snapshot",
]

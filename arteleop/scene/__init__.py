"""The remote site: workspace, bowl, head RGB-D camera, point clouds, depth meshes, tracking."""

from arteleop.scene.bowl import BowlSpec, CollisionBox, bowl_collision_boxes, bowl_mesh
from arteleop.scene.bowl_tracking import BowlTrack, BowlTracker, BowlTrackerConfig
from arteleop.scene.camera import CameraIntrinsics, HeadCamera, HeadCameraConfig, RGBDFrame
from arteleop.scene.depth_mesh import DepthMesh, MeshReconstructor, MeshReconstructorConfig
from arteleop.scene.depth_noise import DepthNoiseConfig, apply_depth_noise
from arteleop.scene.pointcloud import PointCloud, depth_to_camera_points, frame_to_point_cloud
from arteleop.scene.site import GRASP_DEPTH_M, RemoteSite, SiteConfig
from arteleop.scene.snapshot import SceneSnapshot, write_snapshot
from arteleop.scene.workspace import Workspace

__all__ = [
    "GRASP_DEPTH_M",
    "BowlSpec",
    "BowlTrack",
    "BowlTracker",
    "BowlTrackerConfig",
    "CameraIntrinsics",
    "CollisionBox",
    "DepthMesh",
    "DepthNoiseConfig",
    "HeadCamera",
    "HeadCameraConfig",
    "MeshReconstructor",
    "MeshReconstructorConfig",
    "PointCloud",
    "RGBDFrame",
    "RemoteSite",
    "SceneSnapshot",
    "SiteConfig",
    "Workspace",
    "apply_depth_noise",
    "bowl_collision_boxes",
    "bowl_mesh",
    "depth_to_camera_points",
    "frame_to_point_cloud",
    "write_snapshot",
]

"""The head RGB-D camera: a Kinect-360-like sensor fixed on top of Baxter's head.

Frames:
- the camera frame is the optical frame of OpenCV: x right, y down, z forward (m);
- ``T_base_camera`` maps camera coordinates into Baxter's base frame.
Depth images hold the z coordinate in the camera frame (m), 0 where there is no valid return.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pybullet as p
from numpy.typing import ArrayLike, NDArray
from pybullet_utils.bullet_client import BulletClient

from arteleop.errors import CameraConfigError, ConfigurationError
from arteleop.scene.depth_noise import DepthNoiseConfig, apply_depth_noise
from arteleop.transforms import invert_transform, make_transform, transform_points

# OpenCV optical frame -> OpenGL camera frame (x right, y up, looking along -z).
_T_CV_GL = np.diag([1.0, -1.0, -1.0, 1.0])


@dataclass(frozen=True)
class CameraIntrinsics:
    """Pinhole intrinsics in pixels; pixel (0, 0) is the centre of the top-left pixel."""

    width_px: int
    height_px: int
    fx_px: float
    fy_px: float
    cx_px: float
    cy_px: float

    @classmethod
    def from_horizontal_fov(
        cls, width_px: int, height_px: int, hfov_deg: float
    ) -> CameraIntrinsics:
        """Square pixels, centred principal point, horizontal field of view ``hfov_deg``."""
        if not 1.0 < hfov_deg < 179.0:
            raise ConfigurationError(
                f"horizontal field of view must be in (1, 179) deg, got {hfov_deg}"
            )
        f = 0.5 * width_px / np.tan(np.radians(hfov_deg) / 2)
        return cls(width_px, height_px, float(f), float(f), (width_px - 1) / 2, (height_px - 1) / 2)

    @property
    def K(self) -> NDArray[np.float64]:
        """3x3 camera matrix."""
        return np.array([[self.fx_px, 0, self.cx_px], [0, self.fy_px, self.cy_px], [0, 0, 1.0]])

    @property
    def fov_deg(self) -> tuple[float, float]:
        """(horizontal, vertical) field of view in degrees."""
        return (
            float(np.degrees(2 * np.arctan(0.5 * self.width_px / self.fx_px))),
            float(np.degrees(2 * np.arctan(0.5 * self.height_px / self.fy_px))),
        )

    def strided(self, stride: int) -> CameraIntrinsics:
        """Intrinsics of the image that keeps every ``stride``-th row and column.

        Pixel (i, j) of the thinned image is pixel (i * stride, j * stride) of this one.
        """
        if stride < 1:
            raise ConfigurationError(f"stride must be >= 1, got {stride}")
        return CameraIntrinsics(
            -(-self.width_px // stride),
            -(-self.height_px // stride),
            self.fx_px / stride,
            self.fy_px / stride,
            self.cx_px / stride,
            self.cy_px / stride,
        )

    def project(self, points_camera_m: ArrayLike) -> NDArray[np.float64]:
        """Project (N, 3) camera-frame points to (N, 2) pixel coordinates (u right, v down)."""
        pts = np.atleast_2d(np.asarray(points_camera_m, dtype=np.float64))
        return np.column_stack(
            [
                self.fx_px * pts[:, 0] / pts[:, 2] + self.cx_px,
                self.fy_px * pts[:, 1] / pts[:, 2] + self.cy_px,
            ]
        )

    def opengl_projection(self, near_m: float, far_m: float) -> NDArray[np.float64]:
        """4x4 OpenGL projection matrix equivalent to these intrinsics (row-major)."""
        w, h = self.width_px, self.height_px
        return np.array(
            [
                [2 * self.fx_px / w, 0.0, 1 - 2 * (self.cx_px + 0.5) / w, 0.0],
                [0.0, 2 * self.fy_px / h, 2 * (self.cy_px + 0.5) / h - 1, 0.0],
                [
                    0.0,
                    0.0,
                    -(far_m + near_m) / (far_m - near_m),
                    -2 * far_m * near_m / (far_m - near_m),
                ],
                [0.0, 0.0, -1.0, 0.0],
            ]
        )


@dataclass(frozen=True)
class HeadCameraConfig:
    """The head-mounted RGB-D sensor.

    Attributes:
        width_px, height_px: Image size; 640x480 like the Kinect 360.
        horizontal_fov_deg: 57 deg horizontal gives about 44 deg vertical with square pixels.
        rate_hz: Frame rate (Hz).
        min_depth_m, max_depth_m: Valid depth range (m); other pixels read 0.
        mount_link: Robot link the sensor is fixed to (the head is never panned).
        mount_xyz_m: Optical centre in the mount link's frame (m): on top of the head.
        pitch_down_deg: Tilt of the optical axis below the head's forward direction.
        yaw_deg: Turn of the optical axis about the head's z axis (positive to the left).
        noise: Depth error model.
        near_clip_m, far_clip_m: Rendering clip planes (m).
    """

    width_px: int = 640
    height_px: int = 480
    horizontal_fov_deg: float = 57.0
    rate_hz: float = 30.0
    min_depth_m: float = 0.8
    max_depth_m: float = 4.0
    mount_link: str = "head"
    mount_xyz_m: tuple[float, float, float] = (0.16, 0.0, 0.20)
    pitch_down_deg: float = 58.0
    yaw_deg: float = -20.0
    noise: DepthNoiseConfig = field(default_factory=DepthNoiseConfig)
    near_clip_m: float = 0.05
    far_clip_m: float = 6.0

    def __post_init__(self) -> None:
        if self.width_px < 8 or self.height_px < 8:
            raise ConfigurationError(
                f"camera image {self.width_px}x{self.height_px} px is too small"
            )
        if not 0 < self.min_depth_m < self.max_depth_m:
            raise ConfigurationError(
                f"depth range [{self.min_depth_m}, {self.max_depth_m}] m must satisfy 0 < min < max"
            )
        if not 0 < self.near_clip_m < self.min_depth_m or self.far_clip_m <= self.max_depth_m:
            raise ConfigurationError(
                f"clip planes [{self.near_clip_m}, {self.far_clip_m}] m must enclose the depth "
                f"range [{self.min_depth_m}, {self.max_depth_m}] m"
            )
        if self.rate_hz <= 0:
            raise ConfigurationError(f"camera rate_hz must be > 0, got {self.rate_hz}")

    @property
    def intrinsics(self) -> CameraIntrinsics:
        return CameraIntrinsics.from_horizontal_fov(
            self.width_px, self.height_px, self.horizontal_fov_deg
        )

    def T_mount_camera(self) -> NDArray[np.float64]:
        """Pose of the optical frame in the mount link's frame."""
        pitch, yaw = np.radians(self.pitch_down_deg), np.radians(self.yaw_deg)
        z = np.array([np.cos(pitch) * np.cos(yaw), np.cos(pitch) * np.sin(yaw), -np.sin(pitch)])
        x = np.cross(z, [0.0, 0.0, 1.0])
        x /= np.linalg.norm(x)
        y = np.cross(z, x)
        return make_transform(np.column_stack([x, y, z]), self.mount_xyz_m)


@dataclass(frozen=True)
class RGBDFrame:
    """One RGB-D frame with everything needed to interpret it.

    Attributes:
        rgb: (H, W, 3) uint8 colour image.
        depth_m: (H, W) float32 depth along the optical axis (m); 0 = no valid return.
        intrinsics: Pinhole intrinsics of both images (they are registered).
        T_base_camera: Pose of the optical frame in Baxter's base frame.
        timestamp_s: Simulation time of the exposure (s).
        segmentation: (H, W) int32 PyBullet body id per pixel (-1 background), if requested.
            Ground truth for tests and evaluation; trackers must not use it.
    """

    rgb: NDArray[np.uint8]
    depth_m: NDArray[np.float32]
    intrinsics: CameraIntrinsics
    T_base_camera: NDArray[np.float64]
    timestamp_s: float
    segmentation: NDArray[np.int32] | None = None


@dataclass(frozen=True)
class RenderRequest:
    """One image to render: size (px), OpenGL view and projection matrices (16 floats each,
    column-major, as PyBullet takes them), and whether to return the segmentation mask."""

    width_px: int
    height_px: int
    view_gl: list[float]
    projection_gl: list[float]
    with_segmentation: bool = False


@dataclass(frozen=True)
class RawImage:
    """The renderer's output before any sensor model.

    Attributes:
        rgba: (H, W, 4) uint8 colour.
        zbuf: (H, W) float32 OpenGL depth buffer, 0 (near clip) .. 1 (far clip or nothing).
        segmentation: (H, W) int32 PyBullet mask (body id + (link + 1) << 24, -1 background).
    """

    rgba: NDArray[np.uint8]
    zbuf: NDArray[np.float32]
    segmentation: NDArray[np.int32] | None = None


def render(client: BulletClient, request: RenderRequest) -> RawImage:
    """Render ``request`` in ``client`` with the CPU TinyRenderer (no shadows)."""
    w, h = request.width_px, request.height_px
    _, _, rgba, zbuf, seg = client.getCameraImage(
        w,
        h,
        request.view_gl,
        request.projection_gl,
        shadow=0,
        renderer=p.ER_TINY_RENDERER,
        flags=0 if request.with_segmentation else p.ER_NO_SEGMENTATION_MASK,
    )
    return RawImage(
        np.asarray(rgba, dtype=np.uint8).reshape(h, w, 4),
        np.asarray(zbuf, dtype=np.float32).reshape(h, w),
        np.asarray(seg, dtype=np.int32).reshape(h, w) if request.with_segmentation else None,
    )


class HeadCamera:
    """Renders RGB-D frames of a PyBullet scene with the CPU TinyRenderer."""

    def __init__(
        self,
        client: BulletClient,
        config: HeadCameraConfig,
        T_base_mount: NDArray[np.float64],
        rng: np.random.Generator,
    ) -> None:
        self._client = client
        self.config = config
        self.intrinsics = config.intrinsics
        self.T_base_camera = T_base_mount @ config.T_mount_camera()
        self.T_base_camera.setflags(write=False)
        self._T_camera_base = invert_transform(self.T_base_camera)
        self._rng = rng
        self._projection = self.intrinsics.opengl_projection(config.near_clip_m, config.far_clip_m)
        view = invert_transform(self.T_base_camera @ _T_CV_GL)
        # PyBullet takes OpenGL matrices as 16 floats in column-major order.
        self._view_gl = view.T.ravel().tolist()
        self._proj_gl = self._projection.T.ravel().tolist()

    def request(self, with_segmentation: bool = False) -> RenderRequest:
        """What to render for one frame: image size and the camera's OpenGL matrices."""
        c = self.config
        return RenderRequest(
            c.width_px, c.height_px, self._view_gl, self._proj_gl, with_segmentation
        )

    def capture(self, timestamp_s: float, with_segmentation: bool = False) -> RGBDFrame:
        """Render one frame of the client's current state."""
        return self.frame(render(self._client, self.request(with_segmentation)), timestamp_s)

    def frame(self, raw: RawImage, timestamp_s: float) -> RGBDFrame:
        """Turn a rendered image into a frame: metric depth, the sensor's noise and range."""
        c = self.config
        rgb = raw.rgba[..., :3].copy()
        zbuf = raw.zbuf.astype(np.float64)
        n, f = c.near_clip_m, c.far_clip_m
        depth = f * n / (f - (f - n) * zbuf)
        depth[zbuf >= 1.0] = 0.0  # background: nothing rendered there
        depth = apply_depth_noise(
            depth.astype(np.float32), self.intrinsics.fx_px, c.noise, self._rng
        )
        depth[(depth < c.min_depth_m) | (depth > c.max_depth_m)] = 0.0
        segmentation = None
        if raw.segmentation is not None:
            segmentation = raw.segmentation & ((1 << 24) - 1)
            segmentation[raw.segmentation < 0] = -1
        return RGBDFrame(rgb, depth, self.intrinsics, self.T_base_camera, timestamp_s, segmentation)

    def locate(self, point_base_m: ArrayLike) -> tuple[float, float, float]:
        """Pixel (u, v) and depth z (m) of a base-frame point; u and v are nan behind the camera."""
        pc = transform_points(self._T_camera_base, np.atleast_2d(point_base_m))[0]
        if pc[2] <= 0:
            return math.nan, math.nan, float(pc[2])
        u, v = self.intrinsics.project(pc)[0]
        return float(u), float(v), float(pc[2])

    def sees(self, point_base_m: ArrayLike, margin_px: float = 0.0) -> bool:
        """Whether a base-frame point is in the image (with a margin) and in the depth range."""
        u, v, z = self.locate(point_base_m)
        c = self.config
        return (
            c.min_depth_m <= z <= c.max_depth_m
            and margin_px <= u <= c.width_px - 1 - margin_px
            and margin_px <= v <= c.height_px - 1 - margin_px
        )

    def check_sees(
        self, points_base_m: dict[str, NDArray[np.float64]], margin_px: int = 10
    ) -> None:
        """Raise :class:`CameraConfigError` unless every named point is in view and in range."""
        c = self.config
        for name, point in points_base_m.items():
            if self.sees(point, margin_px):
                continue
            u, v, z = self.locate(point)
            where = np.round(point, 3).tolist()
            if not c.min_depth_m <= z <= c.max_depth_m:
                raise CameraConfigError(
                    f"The head camera can't see the {name} at {where} m: it lies {z:.2f} m along "
                    f"the optical axis, outside the depth range [{c.min_depth_m}, "
                    f"{c.max_depth_m}] m. Adjust HeadCameraConfig.pitch_down_deg, yaw_deg or "
                    "mount_xyz_m."
                )
            raise CameraConfigError(
                f"The head camera can't see the {name} at {where} m: it projects to pixel "
                f"({u:.0f}, {v:.0f}), outside the {c.width_px}x{c.height_px} image. Adjust "
                "HeadCameraConfig.pitch_down_deg, yaw_deg or mount_xyz_m."
            )

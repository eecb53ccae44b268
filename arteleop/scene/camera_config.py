"""The head camera's configuration and pinhole intrinsics: plain data, no renderer.

Frames: the camera frame is the optical frame of OpenCV (x right, y down, z forward, m).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from arteleop.errors import ConfigurationError
from arteleop.scene.depth_noise import DepthNoiseConfig
from arteleop.transforms import make_transform, rotvecs_to_matrices


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
        """4x4 OpenGL projection matrix (row-major) with which PyBullet's TinyRenderer draws
        the image these intrinsics describe.

        TinyRenderer samples each pixel at its corner, not its centre, and counts rows from the
        bottom: the principal point sits half a pixel off where OpenGL's convention would put
        it. Measured with ArUco corners (sub-pixel) against their projections: the convention's
        matrix left a mean offset of (+0.52, -0.51) px, this one (0.02, 0.04) px.
        """
        w, h = self.width_px, self.height_px
        return np.array(
            [
                [2 * self.fx_px / w, 0.0, 1 - 2 * self.cx_px / w, 0.0],
                [0.0, 2 * self.fy_px / h, 2 * (self.cy_px + 1) / h - 1, 0.0],
                [
                    0.0,
                    0.0,
                    -(far_m + near_m) / (far_m - near_m),
                    -2 * far_m * near_m / (far_m - near_m),
                ],
                [0.0, 0.0, -1.0, 0.0],
            ]
        )


RENDERERS = ("auto", "gl", "tiny")
"""The head camera's renderers (:attr:`HeadCameraConfig.renderer`)."""


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
        registration_offset_mm, registration_offset_deg: How far the pose the remote system
            uses for the camera (its registration: to place the point cloud, the tracked bowl
            and the operator's eye in the base frame) is from the true pose: a translation (mm)
            and a rotation vector (deg), both in the true optical frame. Zero is a perfect
            registration; the renderer always uses the true pose. ``arteleop calibrate``
            measures what calibration brings such an error down to.
        registered_pose: Instead of the offsets, the pose itself (``T_base_camera``, 4x4 rows,
            m), e.g. the ``base -> head_camera`` edge of ``arteleop calibrate``'s graph file.
        renderer: What draws the frames: ``"gl"`` (OpenGL through EGL, on the CPU or a GPU),
            ``"tiny"`` (PyBullet's TinyRenderer, several times slower) or ``"auto"`` (GL where
            a context opens, TinyRenderer elsewhere). Both give the same colours and depth to
            microns away from silhouettes (``arteleop.scene.gl_renderer``).
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
    registration_offset_mm: tuple[float, float, float] = (0.0, 0.0, 0.0)
    registration_offset_deg: tuple[float, float, float] = (0.0, 0.0, 0.0)
    registered_pose: tuple[tuple[float, ...], ...] | None = None
    renderer: str = "auto"

    def __post_init__(self) -> None:
        if self.renderer not in RENDERERS:
            raise ConfigurationError(
                f"--renderer {self.renderer}: expected auto, gl or tiny (auto: OpenGL where an "
                "EGL context opens, PyBullet's TinyRenderer elsewhere)"
            )
        if self.width_px < 8 or self.height_px < 8:
            raise ConfigurationError(
                f"camera image {self.width_px}x{self.height_px} px is too small: --width-px and "
                "--height-px must each be at least 8 (the Kinect's is 640x480)"
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
        if self.registered_pose is not None:
            try:
                T = np.asarray(self.registered_pose, dtype=np.float64)
            except (TypeError, ValueError):
                T = np.full(1, np.nan)
            offsets = any(self.registration_offset_mm) or any(self.registration_offset_deg)
            rigid = T.shape == (4, 4) and np.isfinite(T).all()
            rigid = rigid and np.abs(T[:3, :3].T @ T[:3, :3] - np.eye(3)).max() < 1e-6
            if offsets or not rigid or np.abs(T[3] - (0, 0, 0, 1)).max() > 1e-12:
                raise ConfigurationError(
                    "HeadCameraConfig.registered_pose: expected a rigid 4x4 transform, and no "
                    "registration offsets beside it (give the pose or the offsets)"
                )
        for name, limit, unit in (
            ("registration_offset_mm", 500.0, "mm"),
            ("registration_offset_deg", 45.0, "deg"),
        ):
            value = np.asarray(getattr(self, name), dtype=np.float64)
            if value.shape != (3,) or not np.isfinite(value).all() or np.linalg.norm(value) > limit:
                option = "--camera-offset-" + unit
                raise ConfigurationError(
                    f"{option} {' '.join(map(str, np.ravel(value).tolist()))}: expected three "
                    f"numbers ({unit}, camera frame) whose length is at most {limit:.0f} {unit}"
                )

    @property
    def intrinsics(self) -> CameraIntrinsics:
        return CameraIntrinsics.from_horizontal_fov(
            self.width_px, self.height_px, self.horizontal_fov_deg
        )

    def T_base_registered(self, T_base_camera_true: NDArray[np.float64]) -> NDArray[np.float64]:
        """The pose the system uses for the camera, given the true one."""
        if self.registered_pose is not None:
            return np.array(self.registered_pose, dtype=np.float64)
        return T_base_camera_true @ self.T_camera_registered()

    def T_camera_registered(self) -> NDArray[np.float64]:
        """The registered optical frame in the true one (the registration's error)."""
        rotvec = np.radians(np.asarray(self.registration_offset_deg, dtype=np.float64))
        return make_transform(
            rotvecs_to_matrices(rotvec), np.asarray(self.registration_offset_mm) / 1000.0
        )

    def T_mount_camera(self) -> NDArray[np.float64]:
        """Pose of the optical frame in the mount link's frame."""
        pitch, yaw = np.radians(self.pitch_down_deg), np.radians(self.yaw_deg)
        z = np.array([np.cos(pitch) * np.cos(yaw), np.cos(pitch) * np.sin(yaw), -np.sin(pitch)])
        x = np.cross(z, [0.0, 0.0, 1.0])
        x /= np.linalg.norm(x)
        y = np.cross(z, x)
        return make_transform(np.column_stack([x, y, z]), self.mount_xyz_m)

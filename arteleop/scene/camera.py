"""The head RGB-D camera: a Kinect-360-like sensor fixed on top of Baxter's head.

Frames:
- the camera frame is the optical frame of OpenCV: x right, y down, z forward (m);
- ``T_base_camera`` maps camera coordinates into Baxter's base frame.
Depth images hold the z coordinate in the camera frame (m), 0 where there is no valid return.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import pybullet as p
from numpy.typing import NDArray
from pybullet_utils.bullet_client import BulletClient

from arteleop.errors import ConfigurationError
from arteleop.scene.camera_config import CameraIntrinsics, HeadCameraConfig
from arteleop.scene.camera_geometry import CameraGeometry
from arteleop.scene.depth_noise import apply_depth_noise
from arteleop.transforms import invert_transform

# OpenCV optical frame -> OpenGL camera frame (x right, y up, looking along -z).
_T_CV_GL = np.diag([1.0, -1.0, -1.0, 1.0])


@dataclass(frozen=True)
class RGBDFrame:
    """One RGB-D frame with everything needed to interpret it.

    Attributes:
        rgb: (H, W, 3) uint8 colour image.
        depth_m: (H, W) float32 depth along the optical axis (m); 0 = no valid return.
        intrinsics: Pinhole intrinsics of both images (they are registered).
        T_base_camera: Pose of the optical frame in Baxter's base frame, as the remote system
            has it registered (``HeadCamera.registered``): the true pose unless
            ``HeadCameraConfig.registration_offset_*`` says otherwise.
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
    column-major, as PyBullet takes them), whether to return the segmentation mask, and
    ``stride``: return every stride-th row and column of the full-size image (a display that
    shows a thinned cloud needs no more, and the rest need not be copied or noised)."""

    width_px: int
    height_px: int
    view_gl: list[float]
    projection_gl: list[float]
    with_segmentation: bool = False
    stride: int = 1

    def __post_init__(self) -> None:
        if not (isinstance(self.stride, int) and self.stride >= 1):
            raise ConfigurationError(
                f"RenderRequest.stride={self.stride!r}: expected a whole number, 1 or more"
            )


@dataclass(frozen=True)
class RawImage:
    """The renderer's output before any sensor model.

    Attributes:
        rgba: (H, W, 4) uint8 colour.
        zbuf: (H, W) float32 OpenGL depth buffer, 0 (near clip) .. 1 (far clip or nothing).
        segmentation: (H, W) int32 PyBullet mask (body id + (link + 1) << 24, -1 background).
        stride: The image keeps every stride-th row and column of the rendered one.
    """

    rgba: NDArray[np.uint8]
    zbuf: NDArray[np.float32]
    segmentation: NDArray[np.int32] | None = None
    stride: int = 1

    def thinned(self, stride: int) -> RawImage:
        """Every ``stride``-th row and column of this image (pixel (0, 0) kept), contiguous."""
        if stride == 1:
            return self
        keep = (slice(None, None, stride), slice(None, None, stride))
        seg = self.segmentation
        return RawImage(
            np.ascontiguousarray(self.rgba[keep]),
            np.ascontiguousarray(self.zbuf[keep]),
            None if seg is None else np.ascontiguousarray(seg[keep]),
            self.stride * stride,
        )


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
    """Renders RGB-D frames of a PyBullet scene with the CPU TinyRenderer.

    A frame's depth noise is drawn from ``seed`` and the frame's timestamp alone, not from the
    frames rendered before it: a frame rendered on demand (the tracker's, or only when needed)
    is the frame an every-tick render would have given at that instant.
    """

    def __init__(
        self,
        render: Callable[[RenderRequest], RawImage],
        config: HeadCameraConfig,
        T_base_mount: NDArray[np.float64],
        seed: int,
    ) -> None:
        self._render = render
        self.config = config
        self.intrinsics = config.intrinsics
        self.geometry = CameraGeometry(config, T_base_mount @ config.T_mount_camera())
        """True pose and field of view: what the camera can see, without rendering."""
        self.T_base_camera = self.geometry.T_base_camera
        """The true pose (the simulator's): for rendering and for measuring errors."""
        self.registered = CameraGeometry(config, config.T_base_registered(self.T_base_camera))
        """The pose the remote system uses for the camera: its frames carry it."""
        self._seed = seed
        self._projection = self.intrinsics.opengl_projection(config.near_clip_m, config.far_clip_m)
        view = invert_transform(self.T_base_camera @ _T_CV_GL)
        # PyBullet takes OpenGL matrices as 16 floats in column-major order.
        self._view_gl = view.T.ravel().tolist()
        self._proj_gl = self._projection.T.ravel().tolist()

    def request(self, with_segmentation: bool = False, stride: int = 1) -> RenderRequest:
        """What to render for one frame: image size and the camera's OpenGL matrices; the
        frame keeps every ``stride``-th row and column."""
        c = self.config
        return RenderRequest(
            c.width_px, c.height_px, self._view_gl, self._proj_gl, with_segmentation, stride
        )

    def capture(self, timestamp_s: float, with_segmentation: bool = False) -> RGBDFrame:
        """Render one frame of the scene's current state."""
        return self.frame(self._render(self.request(with_segmentation)), timestamp_s)

    def frame(self, raw: RawImage, timestamp_s: float) -> RGBDFrame:
        """Turn a rendered image into a frame: metric depth, the sensor's noise and range.

        A thinned image (:attr:`RawImage.stride`) gives a frame of the thinned size with its
        intrinsics; its pixels' noise has the full-size frame's distribution (drawn per pixel,
        quantised at the sensor's own disparity steps), not the same draws.
        """
        c = self.config
        rgb = raw.rgba[..., :3].copy()
        zbuf = raw.zbuf.astype(np.float64)
        n, f = c.near_clip_m, c.far_clip_m
        depth = f * n / (f - (f - n) * zbuf)
        depth[zbuf >= 1.0] = 0.0  # background: nothing rendered there
        # The frame's instant in microseconds: distinct for any two camera ticks.
        rng = np.random.default_rng((self._seed, round(timestamp_s * 1e6)))
        depth = apply_depth_noise(depth.astype(np.float32), self.intrinsics.fx_px, c.noise, rng)
        depth[(depth < c.min_depth_m) | (depth > c.max_depth_m)] = 0.0
        segmentation = None
        if raw.segmentation is not None:
            segmentation = raw.segmentation & ((1 << 24) - 1)
            segmentation[raw.segmentation < 0] = -1
        T = self.registered.T_base_camera
        K = self.intrinsics.strided(raw.stride)
        return RGBDFrame(rgb, depth, K, T, timestamp_s, segmentation)

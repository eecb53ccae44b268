"""Options and checks that several commands share."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal

from arteleop.errors import ConfigurationError, FrameGraphError

if TYPE_CHECKING:
    from arteleop.scene import HeadCameraConfig


Modality = Literal["none", "manipulation", "embodiment", "task", "full", "predictive"]
"""The AR modalities (docs/explanation/study.md §3), as the command line offers them."""

Renderer = Literal["auto", "gl", "tiny"]
"""The head camera's renderers (``HeadCameraConfig.renderer``)."""


def check_seed(seed: int) -> None:
    if seed < 0:
        raise ConfigurationError(f"--seed {seed}: a seed is a whole number, 0 or more.")


@dataclass(frozen=True)
class CameraSize:
    """The head camera's image size, shared by the commands that render it."""

    width_px: int = 640
    """camera image width (px)"""
    height_px: int = 480
    """camera image height (px)"""
    renderer: Renderer = "auto"
    """what draws the head camera: 'gl' (OpenGL through EGL, on the CPU or a GPU), 'tiny' (PyBullet's TinyRenderer, several times slower), 'auto' (gl where it opens, else tiny)"""
    camera_offset_mm: tuple[float, float, float] = (0.0, 0.0, 0.0)
    """a mis-registered camera: the pose the system uses for it (for the point cloud, the tracked bowl, the operator's eye) is the true one moved by this (mm, camera frame: x right, y down, z forward), while the ghost and the target stay where they are"""
    camera_offset_deg: tuple[float, float, float] = (0.0, 0.0, 0.0)
    """the registration's rotation error, a rotation vector (deg, camera frame)"""
    camera_graph: Path | None = None
    """a transform graph file (from 'arteleop calibrate') whose base -> head_camera edge is the camera's pose as the system uses it, instead of --camera-offset-*"""

    def camera_config(self, **overrides: Any) -> HeadCameraConfig:
        from arteleop.frames import TransformGraph
        from arteleop.scene import BASE_FRAME, CAMERA_FRAME, HeadCameraConfig

        registration: dict[str, Any] = {
            "registration_offset_mm": self.camera_offset_mm,
            "registration_offset_deg": self.camera_offset_deg,
        }
        if self.camera_graph is not None:
            if any(self.camera_offset_mm) or any(self.camera_offset_deg):
                raise ConfigurationError(
                    "--camera-graph and --camera-offset-mm/--camera-offset-deg: give one of them"
                )
            graph = TransformGraph.load(self.camera_graph)  # its errors name the file
            try:
                T = graph.T(BASE_FRAME, CAMERA_FRAME)
            except FrameGraphError as err:
                raise FrameGraphError(
                    f"--camera-graph {self.camera_graph}: {err}. 'arteleop calibrate' writes "
                    "such a file, with the edge base -> head_camera."
                ) from None
            registration = {"registered_pose": tuple(tuple(row) for row in T.tolist())}
        return HeadCameraConfig(
            width_px=self.width_px, height_px=self.height_px, renderer=self.renderer,
            **registration, **overrides,
        )  # fmt: skip

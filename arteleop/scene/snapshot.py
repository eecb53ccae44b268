"""Write one head-camera frame of the site to disk: the `arteleop scene` command's job."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import cv2
import numpy as np
from numpy.typing import NDArray

from arteleop.errors import ArteleopError
from arteleop.scene.bowl_tracking import BowlTrack, BowlTracker
from arteleop.scene.camera import RGBDFrame
from arteleop.scene.pointcloud import frame_to_point_cloud
from arteleop.scene.site import RemoteSite

SETTLE_S = 0.5
"""Simulated time the site runs before the snapshot, so the bowl has come to rest (s)."""


@dataclass(frozen=True)
class SceneSnapshot:
    """What `arteleop scene` produced: the frame, the files and the tracking result."""

    frame: RGBDFrame
    track: BowlTrack
    bowl_true_m: NDArray[np.float64]
    files: dict[str, Path]

    @property
    def tracking_error_m(self) -> float | None:
        """Euclidean distance between tracked and true bowl position (m), if tracked."""
        if self.track.position_m is None:
            return None
        return float(np.linalg.norm(self.track.position_m - self.bowl_true_m))


def depth_false_colour(depth_m: NDArray[np.float32]) -> NDArray[np.uint8]:
    """(H, W, 3) BGR picture of a depth image: near red to far blue over the valid range of
    the image, no return black. A 16-bit depth image in millimetres looks black in viewers."""
    valid = depth_m > 0
    out = np.zeros((*depth_m.shape, 3), np.uint8)
    if valid.any():
        near, far = float(depth_m[valid].min()), float(depth_m[valid].max())
        scaled = (depth_m - near) / max(far - near, 1e-6) * 255
        colours = cv2.applyColorMap(
            np.clip(255 - scaled, 0, 255).astype(np.uint8), cv2.COLORMAP_JET
        )
        out[valid] = colours[valid]
    return out


def write_snapshot(site: RemoteSite, out_dir: Path) -> SceneSnapshot:
    """Let the site settle, capture one frame and write rgb.png, depth.png, depth_vis.png and
    cloud.ply.

    depth.png is 16-bit in millimetres (0 = no return); depth_vis.png shows it in false colour;
    cloud.ply is in the base frame (m).
    """
    from open3d.io import write_point_cloud  # 1.7 s to import: only for a snapshot

    out_dir.mkdir(parents=True, exist_ok=True)
    site.step(round(SETTLE_S * site.config.physics_rate_hz))
    frame = site.capture()
    names = ("rgb.png", "depth.png", "depth_vis.png", "cloud.ply")
    files = {name: out_dir / name for name in names}
    depth_mm = np.round(frame.depth_m.astype(np.float64) * 1000.0).clip(0, 65535).astype(np.uint16)
    ok = cv2.imwrite(str(files["rgb.png"]), cv2.cvtColor(frame.rgb, cv2.COLOR_RGB2BGR))
    ok &= cv2.imwrite(str(files["depth.png"]), depth_mm)
    ok &= cv2.imwrite(str(files["depth_vis.png"]), depth_false_colour(frame.depth_m))
    ok &= write_point_cloud(str(files["cloud.ply"]), frame_to_point_cloud(frame).to_open3d())
    if not ok:
        raise ArteleopError(f"Could not write the snapshot files into {out_dir}: is it writable?")
    track = BowlTracker(site.config.workspace.bowl).track(
        frame, site.config.workspace.table_top_z_m
    )
    return SceneSnapshot(frame, track, site.observe(links=()).bowl_m.copy(), files)

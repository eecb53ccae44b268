"""'arteleop scene': one head-camera frame of the site at rest, written, and the bowl tracked."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Annotated

import tyro

from arteleop.cli.options import CameraSize, check_seed


@dataclass(frozen=True)
class SceneCommand(CameraSize):
    """Render one head-camera frame of the remote site at rest and track the bowl."""

    out: Annotated[
        Path,
        tyro.conf.arg(
            help="folder for rgb.png, depth.png (16-bit mm), depth_vis.png (false colour) and "
            "cloud.ply (base frame, m)"
        ),
    ] = field(default=Path("arteleop-scene"))
    seed: int = 0
    """seed of the depth noise (0 or more)"""
    noise: bool = True
    """add Kinect-like depth noise and quantisation"""


def scene(cmd: SceneCommand) -> int:
    from arteleop.scene import DepthNoiseConfig, RemoteSite, SiteConfig, write_snapshot

    check_seed(cmd.seed)
    camera = cmd.camera_config(noise=DepthNoiseConfig(enabled=cmd.noise, quantize=cmd.noise))
    with RemoteSite(SiteConfig(camera=camera, seed=cmd.seed)) as site:
        snap = write_snapshot(site, cmd.out)
    for name, path in snap.files.items():
        print(f"wrote {name:9s} {path}")
    truth = snap.bowl_true_m
    print(
        f"bowl (ground truth)  x={truth[0]:+.4f} y={truth[1]:+.4f} z={truth[2]:+.4f} m (base frame)"
    )
    if not snap.track.found or snap.track.position_m is None:
        print(f"bowl not found: {snap.track.reason}")
        return 1
    est = snap.track.position_m
    print(
        f"bowl (tracked)      x={est[0]:+.4f} y={est[1]:+.4f} z={est[2]:+.4f} m "
        f"from {snap.track.n_points} points"
    )
    print(f"tracking error      {snap.tracking_error_m * 1000:.1f} mm")
    return 0

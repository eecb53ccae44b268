"""The `arteleop` command. Each subcommand's options map one-to-one onto a config dataclass."""

from __future__ import annotations

import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Annotated

import tyro

from arteleop.errors import ArteleopError


@dataclass(frozen=True)
class SceneCommand:
    """Render one head-camera frame of the remote site at rest and track the bowl."""

    out: Annotated[
        Path, tyro.conf.arg(help="folder for rgb.png, depth.png (16-bit mm) and cloud.ply")
    ] = field(default=Path("arteleop-scene"))
    seed: int = 0
    """seed of the depth noise"""
    noise: bool = True
    """add Kinect-like depth noise and quantisation"""
    width_px: int = 640
    height_px: int = 480


def scene(cmd: SceneCommand) -> int:
    from arteleop.scene import (
        DepthNoiseConfig,
        HeadCameraConfig,
        RemoteSite,
        SiteConfig,
        write_snapshot,
    )

    noise = DepthNoiseConfig(enabled=cmd.noise, quantize=cmd.noise)
    camera = HeadCameraConfig(width_px=cmd.width_px, height_px=cmd.height_px, noise=noise)
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


COMMANDS = {"scene": (SceneCommand, scene)}


def main(argv: list[str] | None = None) -> int:
    """Entry point of the `arteleop` command."""
    cmd = tyro.extras.subcommand_cli_from_dict(
        {name: cfg for name, (cfg, _) in COMMANDS.items()},
        prog="arteleop",
        args=argv,
        description="arteleop: study Augmented Reality in robot teleoperation, in simulation.",
    )
    run = next(fn for cfg, fn in COMMANDS.values() if isinstance(cmd, cfg))
    try:
        return run(cmd)
    except ArteleopError as err:
        print(f"arteleop: error: {err}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())

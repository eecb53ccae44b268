"""'arteleop calibrate': register the head camera to the robot and score it against the truth."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Literal

from arteleop.cli.options import CameraSize, check_seed

CalibrationMethod = Literal["best", "tsai", "park", "horaud", "andreff", "daniilidis", "shah", "li"]


@dataclass(frozen=True)
class CalibrateCommand(CameraSize):
    """Register the head camera to the robot, in simulation, with the camera's true pose hidden
    from the solvers: a marker on the table (helper-based) and a board in the gripper shown in
    --poses poses (hand-eye: seven OpenCV methods, the best refined on the marker's corners).
    Prints each estimate's error against the true pose, its reprojection error and the ghost's
    co-location error, and writes the refined estimate, with its covariance, into a transform
    graph file."""

    poses: int = 10
    """hand-eye: poses with the board in view (3 or more)"""
    seed: int = 0
    """seed of the poses and of the marker's placements (0 or more)"""
    method: CalibrationMethod = "best"
    """the closed-form hand-eye estimate that starts the refinement written to --out; 'best' is the one with the lowest reprojection error (which needs no ground truth)"""
    out: Path = Path("calibration.json")
    """transform graph file (JSON) to write: the site's frames (the robot's links at rest, the table, the markers) and the camera's, joined to base by an edge of kind calibration"""


def calibrate(cmd: CalibrateCommand) -> int:
    import numpy as np

    from arteleop.calibration import CalibrationConfig, calibrate_camera, calibration_errors
    from arteleop.frames import EdgeKind
    from arteleop.scene import BASE_FRAME, CAMERA_FRAME, RemoteSite, SiteConfig

    check_seed(cmd.seed)
    config = CalibrationConfig(poses=cmd.poses, seed=cmd.seed)
    with RemoteSite(SiteConfig(camera=cmd.camera_config(), seed=cmd.seed)) as site:
        run = calibrate_camera(site, config, cmd.method)
        T_true = site.camera.T_base_camera
        registered = site.camera.registered.T_base_camera
        intrinsics = site.camera.intrinsics
        graph = site.frames.graph  # the robot at rest, the table, the markers, the camera
    chosen = run.refined
    positions = run.data.T_base_gripper[:, :3, 3]
    print(
        f"hand-eye: {len(positions)} usable poses of {run.data.attempts} tried; helper: "
        f"{run.helper.poses} sightings of the table marker\n"
    )
    print(
        "| method | poses | error (mm) | error (deg) | reprojection (px) "
        "| co-location (px) | co-location (mm) |"
    )
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: |")
    if not np.array_equal(registered, T_true):
        e = calibration_errors(registered, T_true, intrinsics, positions)
        print(
            f"| registration given (--camera-offset-*) | - | {e.error_mm:.1f} | {e.error_deg:.2f} "
            f"| - | {e.colocation_px:.1f} | {e.colocation_mm:.1f} |"
        )
    for r in [run.helper, *run.closed_form, chosen]:
        e = calibration_errors(r.T_base_camera, T_true, intrinsics, positions)
        print(
            f"| {r.method} | {r.poses} | {e.error_mm:.1f} | {e.error_deg:.2f} "
            f"| {r.reprojection_error_px:.2f} | {e.colocation_px:.1f} | {e.colocation_mm:.1f} |"
        )
    graph.set(BASE_FRAME, CAMERA_FRAME, chosen.transform, EdgeKind.CALIBRATION)
    graph.save(cmd.out)
    print(
        f"\nwrote {cmd.out}: the site's frames, with base -> head_camera from {chosen.method} "
        "(co-location is measured at the hand-eye poses' gripper positions)"
    )
    return 0

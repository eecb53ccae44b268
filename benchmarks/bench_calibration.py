"""Calibration of the head camera against the simulator's true pose, for N = 5, 10, 20 poses.

For each N and each seed, runs hand-eye calibration (a board held in the gripper, seven OpenCV
methods, the one with the lowest reprojection error refined on the corners) and the
helper-based calibration (a marker on the table), with the camera's depth noise of the site
(which the RGB image, and so the marker, does not carry). Prints per N and method the medians
over the seeds of the error against the true pose (mm, deg) and of the ghost's co-location
error (px at 640x480, mm). The baseline is the closed-form method with the lowest reprojection
error, the starting point of the refinement, in the same run.

    python benchmarks/bench_calibration.py [--seeds 5] [--poses 5,10,20]

Targets (issue): at most 5 mm and 0.5 deg with 10 poses; co-location under 3 px.
"""

from __future__ import annotations

from arteleop import blas_kernel  # noqa: F401  (first: it picks numpy's BLAS kernel)

# isort: split
import argparse
from collections import defaultdict

import numpy as np

from arteleop.calibration import CalibrationConfig, calibrate_camera, calibration_errors
from arteleop.scene import RemoteSite, SiteConfig


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--seeds", type=int, default=5)
    parser.add_argument("--poses", default="5,10,20")
    args = parser.parse_args()
    rows: dict[tuple[int, str], list[tuple[float, float, float, float]]] = defaultdict(list)
    for n in [int(x) for x in args.poses.split(",")]:
        for seed in range(args.seeds):
            config = CalibrationConfig(poses=n, seed=seed)
            with RemoteSite(SiteConfig(seed=seed)) as site:
                truth, K = site.camera.T_base_camera.copy(), site.camera.intrinsics
                run = calibrate_camera(site, config)
            data, closed = run.data, run.closed_form
            best = min(closed, key=lambda r: r.reprojection_error_px)
            positions = data.T_base_gripper[:, :3, 3]
            named = [
                ("refined (best closed form + corners)", run.refined),
                ("baseline: best closed form", best),
                ("helper (table marker)", run.helper),
            ]
            named += [(r.method, r) for r in closed]  # fmt: skip
            for name, result in named:
                e = calibration_errors(result.T_base_camera, truth, K, positions)
                rows[(n, name)].append((e.error_mm, e.error_deg, e.colocation_px, e.colocation_mm))
            print(f"  N={n} seed {seed}: {len(positions)} poses of {data.attempts} tried, "
                  f"refined from {best.method}", flush=True)  # fmt: skip
    print(f"\n## Camera calibration against ground truth, medians over {args.seeds} seeds\n")
    print("| poses | method | error (mm) | error (deg) | co-location (px) | co-location (mm) |")
    print("| ---: | --- | ---: | ---: | ---: | ---: |")
    for (n, name), values in rows.items():
        m = np.median(np.array(values), axis=0)
        print(f"| {n} | {name} | {m[0]:.1f} | {m[1]:.2f} | {m[2]:.1f} | {m[3]:.1f} |")


if __name__ == "__main__":
    main()

"""Speed of the remote site on one core: physics rate and camera frame rate.

Baseline: the same site with Baxter as installed: the original COLLADA visual meshes, every link
visible and every joint simulated (``render_triangles_per_mesh=None, hidden_links=()``,
``freeze_idle_joints=False``), run side by side in this script.

    python benchmarks/bench_site.py [--repeats N]
"""

from __future__ import annotations

from arteleop import blas_kernel  # noqa: F401  (first: it picks numpy's BLAS kernel)

# isort: split
import os

os.environ.setdefault("OMP_NUM_THREADS", "1")  # before numpy/open3d load their thread pools

import argparse
import statistics
import time
from collections.abc import Callable
from dataclasses import replace

from arteleop.robot import BaxterDescriptionConfig
from arteleop.scene import HeadCameraConfig, RemoteSite, SiteConfig, frame_to_point_cloud

BASELINE = SiteConfig(
    robot=BaxterDescriptionConfig(render_triangles_per_mesh=None, hidden_links=()),
    freeze_idle_joints=False,
)


def interleaved_median_s(fns: dict[str, Callable[[], object]], repeats: int) -> dict[str, float]:
    """Median wall time of each function, alternating them so drifts hit all alike."""
    times: dict[str, list[float]] = {k: [] for k in fns}
    for _ in range(repeats):
        for key, fn in fns.items():
            t0 = time.perf_counter()
            fn()
            times[key].append(time.perf_counter() - t0)
    return {k: statistics.median(v) for k, v in times.items()}


def physics_second(site: RemoteSite, bowl_moving: bool) -> Callable[[], None]:
    """One simulated second; with ``bowl_moving`` the bowl is thrown twice so it never sleeps."""
    steps = round(site.config.physics_rate_hz)
    ws = site.config.workspace

    def run() -> None:
        if not bowl_moving:
            site.step(steps)
            return
        for _ in range(2):
            site.place_bowl(ws.bowl_start_xy_m, (0.3, 0.0, 0.5), (0.0, 2.0, 0.0))
            site.step(steps // 2)

    return run


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--repeats", type=int, default=15)
    args = parser.parse_args()
    if hasattr(os, "sched_setaffinity"):
        os.sched_setaffinity(0, {min(os.sched_getaffinity(0))})
    configs = {"baseline": BASELINE, "arteleop": SiteConfig()}
    results: dict[str, dict[str, float]] = {k: {} for k in configs}

    sites = {k: RemoteSite(c) for k, c in configs.items()}
    for site in sites.values():
        site.step(240)  # let the bowl settle (and sleep)
    n = max(3, args.repeats // 3)
    for moving in (False, True):
        fns = {k: physics_second(s, moving) for k, s in sites.items()}
        for k, t in interleaved_median_s(fns, n).items():
            results[k]["physics_moving" if moving else "physics_rest"] = 1.0 / t
    for site in sites.values():
        site.close()

    for w, h in ((640, 480), (320, 240)):
        cam = HeadCameraConfig(width_px=w, height_px=h)
        sites = {k: RemoteSite(replace(c, camera=cam)) for k, c in configs.items()}
        total = interleaved_median_s(
            {k: (lambda s=s: frame_to_point_cloud(s.capture())) for k, s in sites.items()},
            args.repeats,
        )
        render = interleaved_median_s({k: s.capture for k, s in sites.items()}, args.repeats)
        for k in configs:
            results[k][f"fps_{w}"] = 1.0 / total[k]
            results[k][f"render_ms_{w}"] = 1000.0 * render[k]
        for site in sites.values():
            site.close()

    base, ours = results["baseline"], results["arteleop"]
    print(f"Remote site on one core, medians over {args.repeats} repeats, physics at 240 Hz.")
    print("Baseline: Baxter as installed (original meshes, every link, every joint simulated).\n")
    print("| measure | baseline | arteleop | arteleop / baseline |")
    print("| --- | ---: | ---: | ---: |")
    for key, name, unit in (
        ("physics_rest", "physics, bowl at rest", "x real time"),
        ("physics_moving", "physics, bowl moving", "x real time"),
        ("fps_640", "camera 640x480, render + cloud", "fps"),
        ("render_ms_640", "render alone, 640x480", "ms"),
        ("fps_320", "camera 320x240, render + cloud", "fps"),
        ("render_ms_320", "render alone, 320x240", "ms"),
    ):
        print(
            f"| {name} ({unit}) | {base[key]:.1f} | {ours[key]:.1f} | {ours[key] / base[key]:.2f} |"
        )


if __name__ == "__main__":
    main()

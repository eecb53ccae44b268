"""Transform graph queries: base to gripper on Baxter's URDF, cached and not, against pinocchio.

Prints the median time of one query ``T('base', 'right_gripper')`` on a graph of Baxter's links
(the moving joints as dynamic edges): with nothing changed since the last query (the answer
kept), after the seven arm joints moved (the path cached, fixed runs pre-multiplied; the joint
update itself not timed), with the path searched every time, and with a covariance on every
dynamic edge; beside the baseline of pinocchio's own forward kinematics to the same frame, run
in the same process.

    python benchmarks/bench_frames.py [--repeats 2000]
"""

from __future__ import annotations

from arteleop import blas_kernel  # noqa: F401  (first: it picks numpy's BLAS kernel)

# isort: split
import argparse
import itertools
import time
from collections.abc import Callable

import numpy as np

from arteleop.frames import EdgeKind, RobotFrames, TransformGraph
from arteleop.robot import (
    GRIPPER_FRAME,
    RIGHT_ARM_JOINTS,
    BaxterKinematics,
    load_baxter_description,
)


def median_us(fn: Callable[[], object], repeats: int) -> float:
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return float(np.median(times) * 1e6)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--repeats", type=int, default=2000)
    args = parser.parse_args()
    urdf = load_baxter_description().urdf_path
    positions = dict(zip(RIGHT_ARM_JOINTS, np.linspace(-0.5, 0.5, 7).tolist(), strict=True))
    graph = TransformGraph()
    kinematics = BaxterKinematics(urdf)
    robot = RobotFrames(kinematics)
    robot.attach(graph, positions)
    T_graph = graph.T("base", GRIPPER_FRAME)
    T_pin = kinematics.frame_transform(positions, GRIPPER_FRAME)
    assert np.allclose(T_graph, T_pin, atol=1e-12), "the graph and pinocchio disagree"
    path = graph.path("base", GRIPPER_FRAME)
    edges = [graph.edge(a, b) if (a, b) in {(e.parent, e.child) for e in graph.edges()}
             else graph.edge(b, a) for a, b in itertools.pairwise(path)]  # fmt: skip

    def uncached() -> None:
        graph._paths.clear()  # the benchmark's one look inside: the cost of finding the path
        graph.T("base", GRIPPER_FRAME)

    def after_move(target: TransformGraph, covariance: np.ndarray | None) -> float:
        """Median query time on ``target`` after each move of the arm (the move not timed)."""
        times = []
        for k in range(args.repeats):
            moved = {name: 0.1 * np.sin(k + i) for i, name in enumerate(RIGHT_ARM_JOINTS)}
            robot.update(graph, moved)
            for e in moving_edges:
                target.set(e.parent, e.child, graph.edge(e.parent, e.child).transform.T,
                           EdgeKind.DYNAMIC, covariance)  # fmt: skip
            t0 = time.perf_counter()
            target.lookup("base", GRIPPER_FRAME)
            times.append(time.perf_counter() - t0)
        return float(np.median(times) * 1e6)

    moving_edges = [e for e in edges if e.kind is EdgeKind.DYNAMIC]
    plain, uncertain = TransformGraph(), TransformGraph()
    robot.attach(plain, positions)
    robot.attach(uncertain, positions)
    rows = [
        ("nothing changed since the last query",
         median_us(lambda: graph.T("base", GRIPPER_FRAME), args.repeats)),
        ("after the arm moved, path cached", after_move(plain, None)),
        ("path searched every time", median_us(uncached, args.repeats)),
        ("with covariances, after the arm moved", after_move(uncertain, np.eye(6) * 1e-8)),
    ]  # fmt: skip
    tick = itertools.count()

    def camera_tick() -> None:
        k = next(tick)
        robot.update(graph, {n: 0.1 * np.sin(k + i) for i, n in enumerate(RIGHT_ARM_JOINTS)})
        graph.T("base", GRIPPER_FRAME)

    rows.append(("a display frame: the arm's joints set, then the query (SiteFrames)",
                 median_us(camera_tick, args.repeats)))  # fmt: skip
    rows.append((
        "baseline: pinocchio forward kinematics (BaxterKinematics.frame_transform)",
        median_us(lambda: kinematics.frame_transform(positions, GRIPPER_FRAME), args.repeats),
    ))  # fmt: skip
    print(f"\n## base -> {GRIPPER_FRAME}: {len(path) - 1} edges, {len(moving_edges)} of them moving; "
          f"{len(graph.frames)} frames\n")  # fmt: skip
    print("| query | median (us) | ratio to pinocchio |")
    print("| --- | ---: | ---: |")
    for name, us in rows:
        print(f"| {name} | {us:.1f} | {us / rows[-1][1]:.2f} |")
    print("\nTarget (issue): a cached base-to-gripper query under 20 us.")


if __name__ == "__main__":
    main()

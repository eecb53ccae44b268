"""The remote site's start-up checks: a workspace the right arm can work in, a bowl the gripper
can pinch. Each returns why not (a message naming the setting to change), or None."""

from __future__ import annotations

import numpy as np

from arteleop.robot import TopDownReach
from arteleop.robot.gripper import ElectricGripper
from arteleop.scene.workspace import Workspace


def reach_problem(ws: Workspace, reach: TopDownReach, margin: float) -> str | None:
    """Why the right gripper cannot grasp the bowl's rim from above, on any of its four sides,
    at the workspace's start, target or the bowl's own start (keeping ``margin`` of the arm's
    reach free); None if it can."""
    points = {"start": ws.start_m, "target": ws.target_m}
    if ws.bowl_xy_m is not None:
        points["bowl"] = ws.on_table(ws.bowl_xy_m)
    for name, point in points.items():
        for side in ((1.0, 0.0), (-1.0, 0.0), (0.0, 1.0), (0.0, -1.0)):
            tool = point + ws.bowl.grasp_offset_m(side)
            if not reach.is_reachable(tool, margin):
                xy = tuple(np.round(point[:2], 3).tolist())
                return (
                    f"The {name} point {xy} m is out of the right "
                    f"arm's reach from above: grasping the rim at {np.round(tool, 3).tolist()} "
                    f"needs {reach.reach_fraction(tool):.0%} of the arm's reach, the limit is "
                    f"{1 - margin:.0%} (and at least "
                    f"{reach.min_reach_m / reach.max_reach_m:.0%}). Move Workspace.{name}_xy_m "
                    f"closer to the shoulder at {np.round(reach.shoulder_m[:2], 3).tolist()}."
                )
    return None


def gripper_gap_range_m(gripper: ElectricGripper, rest_closure: float) -> tuple[float, float]:
    """(closed, open) gap between the finger pads (m), measured on the collision shapes; the
    gripper is left at ``rest_closure``."""
    gaps = []
    for closure in (1.0, 0.0):
        gripper.reset(closure)
        gaps.append(gripper.pad_gap_m())
    gripper.reset(rest_closure)
    return gaps[0], gaps[1]


def gripper_span_problem(gap_range_m: tuple[float, float], wall_thickness_m: float) -> str | None:
    """Why a gripper whose pads close to and open to ``gap_range_m`` (m) cannot pinch a bowl wall
    ``wall_thickness_m`` thick (with a fifth of the opening to aim in); None if it can."""
    closed, opened = gap_range_m
    t = wall_thickness_m
    if closed < t < 0.8 * opened:
        return None
    return (
        f"The gripper can't pinch a bowl wall {t * 1000:.1f} mm thick: its pads close to "
        f"{closed * 1000:.1f} mm and open to {opened * 1000:.1f} mm. Choose "
        f"BowlSpec.wall_thickness_m between {closed * 1000:.1f} and "
        f"{0.8 * opened * 1000:.1f} mm (80 % of the opening, to leave room to aim)."
    )

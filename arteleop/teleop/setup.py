"""Assemble a synthetic operator for a site: what the operator knows of the task."""

from __future__ import annotations

import numpy as np

from arteleop.operator.synthetic import Expertise, OperatorParams, TaskGeometry
from arteleop.robot import GRIPPER_FRAME
from arteleop.robot.mapping import HandToGripper
from arteleop.scene import GRASP_DEPTH_M, RemoteSite
from arteleop.teleop.sources import SyntheticSource
from arteleop.teleop.trial import TrialConfig


def synthetic_source(
    site: RemoteSite,
    config: TrialConfig,
    params: OperatorParams | None = None,
    expertise: Expertise | None = None,
) -> SyntheticSource:
    """A synthetic operator who knows the grasp (a rim point facing +y, where the open fingers
    straddle the wall), the rest pose and the mapping, seeded from ``config.seed``."""
    ws = site.config.workspace
    grasp = np.array(
        [0.0, ws.bowl.rim_radius_m - ws.bowl.wall_thickness_m / 2, ws.bowl.height_m - GRASP_DEPTH_M]
    )
    task = TaskGeometry(grasp, site.robot.link_transform(GRIPPER_FRAME)[:3, 3])
    mapping = HandToGripper(config.controller.mapping)
    rng = np.random.default_rng([config.seed, 1])  # a stream of its own, apart from the link's
    return SyntheticSource(task, mapping.hand_position_for, rng, params=params, expertise=expertise)

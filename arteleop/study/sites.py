"""The remote site of each planned trial, and the site's own checks of start and target points,
without starting a simulator."""

from __future__ import annotations

import copy
from collections.abc import Mapping
from dataclasses import replace
from typing import Any

import numpy as np

from arteleop.errors import WorkspaceError
from arteleop.robot import BaxterKinematics, TopDownReach, load_baxter_description
from arteleop.scene import (
    CameraGeometry,
    HeadCameraConfig,
    RemoteSite,
    SiteConfig,
    Workspace,
    landmark_problem,
    reach_problem,
)
from arteleop.study.plan import PracticePoints, TrialSpec

PRACTICE_MARGIN_M = 0.10
"""Practice trials start and end around the experimental task: within this distance (m) of the
box its start and target span, so that practice trains the same reach (docs/explanation/study.md
§4)."""


class StudySite:
    """Builds the :class:`SiteConfig` of each trial from one base configuration.

    Args:
        base: The site every trial shares; each trial sets the bowl's start and target and the
            seed of the depth noise.
    """

    def __init__(self, base: SiteConfig | None = None) -> None:
        self.base = base or SiteConfig()
        description = load_baxter_description(self.base.robot)
        self._kinematics = BaxterKinematics(description.urdf_path)
        self._reach = TopDownReach.from_kinematics(self._kinematics)
        self.camera = self._camera_geometry(self.base.camera)
        """The head camera's true pose and field of view, as every trial's site has it."""
        self._probe: RemoteSite | None = None

    def _camera_geometry(self, camera: HeadCameraConfig) -> CameraGeometry:
        # The head never pans: its pose, and so the camera's, is the same in every configuration.
        T_base_mount = self._kinematics.frame_transform({}, camera.mount_link)
        return CameraGeometry(camera, T_base_mount @ camera.T_mount_camera())

    def with_camera(self, camera: HeadCameraConfig) -> StudySite:
        """The same site seen through another head camera (its trials' frames and images), the
        robot's model not loaded again."""
        other = copy.copy(self)
        other.base = replace(self.base, camera=camera)
        other.camera = self._camera_geometry(camera)
        other._probe = None
        return other

    def seen_at_rest(self, xy_m: tuple[float, float]) -> bool:
        """Whether the head camera's tracker finds the bowl at ``xy_m`` while the arm rests
        (the model of the tracker, :meth:`RemoteSite.sight_bowl`). The synthetic operator
        reaches only for a bowl it has seen, so a practice trial with a hidden bowl would wait
        out its timeout."""
        if self._probe is None:
            self._probe = RemoteSite(self.base)
        self._probe.place_bowl(xy_m)
        return self._probe.sight_bowl().found

    def close(self) -> None:
        """Frees the simulator that :meth:`seen_at_rest` started, if any."""
        if self._probe is not None:
            self._probe.close()
            self._probe = None

    def workspace(
        self, start_xy_m: tuple[float, float], target_xy_m: tuple[float, float]
    ) -> Workspace:
        """The base workspace with the bowl's start and target moved (base frame, m)."""
        return replace(self.base.workspace, start_xy_m=start_xy_m, target_xy_m=target_xy_m,
                       bowl_xy_m=None)  # fmt: skip

    def problem(
        self, start_xy_m: tuple[float, float], target_xy_m: tuple[float, float]
    ) -> str | None:
        """Why the site would refuse this start and target (table, reach, the head camera's
        view), or None."""
        try:
            ws = self.workspace(start_xy_m, target_xy_m)
        except WorkspaceError as err:
            return str(err)
        problem = reach_problem(ws, self._reach, self.base.reach_margin)
        if problem is not None:
            return problem
        for name, point in ws.camera_landmarks_m().items():
            unseen = landmark_problem(self.camera, {name: point})
            if unseen is not None:
                key = "start_xy_m" if "start" in name else "target_xy_m"
                return f"{unseen}. Move Workspace.{key} into the camera's view."
        return None

    def site_config(
        self, spec: TrialSpec, camera_registration: Mapping[str, Any] | None = None
    ) -> SiteConfig:
        """The site of one planned trial, its camera registered as ``camera_registration``
        says (:meth:`StudyConfig.camera_registration`; by default perfectly)."""
        camera = replace(self.base.camera, **(camera_registration or {}))
        return replace(
            self.base,
            workspace=self.workspace(spec.start_xy_m, spec.target_xy_m),
            seed=spec.seed,
            camera=camera,
        )

    def practice_points(
        self, start_xy_m: tuple[float, float], target_xy_m: tuple[float, float]
    ) -> PracticePoints:
        """Practice points within :data:`PRACTICE_MARGIN_M` of the box that the experimental
        start and target span, where the bowl fits on the table, the arm reaches, and the head
        camera sees the bowl at the start while the arm rests."""
        lower, upper = self.base.workspace.table_bounds_xy_m()
        r = self.base.workspace.bowl.rim_radius_m
        points = np.array([start_xy_m, target_xy_m])
        low = np.maximum(points.min(axis=0) - PRACTICE_MARGIN_M, lower + r)
        high = np.minimum(points.max(axis=0) + PRACTICE_MARGIN_M, upper - r)
        return PracticePoints(
            self._practice_problem, (float(low[0]), float(low[1])),
            (float(high[0]), float(high[1])),
        )  # fmt: skip

    def _practice_problem(
        self, start_xy_m: tuple[float, float], target_xy_m: tuple[float, float]
    ) -> str | None:
        problem = self.problem(start_xy_m, target_xy_m)
        if problem is None and not self.seen_at_rest(start_xy_m):
            return f"the head camera does not see the bowl at {start_xy_m} while the arm rests"
        return problem

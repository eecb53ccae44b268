"""A model of the bowl tracker for camera frames that are not rendered.

The tracker (:mod:`arteleop.scene.bowl_tracking`) finds the bowl when the camera sees enough of
it: bowl-coloured pixels with a valid depth. Rendering and tracking every frame costs tens of
milliseconds, so the loop asks this model instead: it casts a ray from the camera to points
spread over the bowl's surface and counts those the camera would see (in the image, in the
sensor's depth range, and not hidden by the arm, by the gripper or by the bowl itself). The bowl
is found when enough of them are seen, at its true position. Its agreement with the tracker is
measured in ``tests/scene/test_bowl_sight.py``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from arteleop.errors import ConfigurationError
from arteleop.scene.bowl import BowlSpec, bowl_mesh
from arteleop.scene.bowl_tracking import BowlTrack
from arteleop.scene.camera_geometry import CameraGeometry
from arteleop.transforms import transform_points


@dataclass(frozen=True)
class BowlSightConfig:
    """Settings of the tracker model.

    Attributes:
        min_visible_fraction: The bowl is found when at least this fraction of its surface
            points is seen. Fitted to the tracker by ``benchmarks/bench_bowl_sight.py``: over
            1851 looks of 30 seeded trials (six per modality, every 0.5 s), 0.3 agrees with
            the tracker on 99.0 % of them, and anything from 0.2 to 0.35 within 0.3 points of
            that; 0.3 sits inside that plateau, away from its fall past 0.35, where the model
            starts to hide a bowl the tracker finds. The remaining disagreements are a partly
            hidden bowl, which the tracker refuses (an arc fits many bowls) and the model, with
            too few points to tell, accepts.
        segments: Surface points around the bowl's axis.
        rings: Rows of surface points up its profile.
        hit_tolerance_m: A ray's first hit this close to its surface point sees that point;
            the collision shape tiles the wall with boxes that stand off the drawn surface by
            a few millimetres.
    """

    min_visible_fraction: float = 0.3
    segments: int = 12
    rings: int = 3
    hit_tolerance_m: float = 0.008

    def __post_init__(self) -> None:
        if not 0 < self.min_visible_fraction <= 1 or self.segments < 3 or self.rings < 1:
            raise ConfigurationError(
                "BowlSightConfig needs 0 < min_visible_fraction <= 1, segments >= 3, rings >= 1; "
                f"got {self.min_visible_fraction}, {self.segments}, {self.rings}"
            )


class BowlSight:
    """What the tracker would report for a state of the site, without rendering it; the site
    casts the rays (``RemoteSite.sight_bowl``)."""

    def __init__(self, spec: BowlSpec, config: BowlSightConfig | None = None) -> None:
        self.config = config = config or BowlSightConfig()
        vertices, _ = bowl_mesh(spec, segments=config.segments, rings=config.rings)
        self._points_bowl = vertices

    @property
    def n_surface_points(self) -> int:
        """How many surface points the model casts a ray to."""
        return len(self._points_bowl)

    def surface_points_m(self, T_base_bowl: NDArray[np.float64]) -> NDArray[np.float64]:
        """The model's surface points in the base frame (m), (N, 3)."""
        return transform_points(T_base_bowl, self._points_bowl)

    def look(
        self,
        T_base_bowl: NDArray[np.float64],
        camera: CameraGeometry,
        hits_m: NDArray[np.float64],
        time_s: float,
    ) -> BowlTrack:
        """The modelled track, given where the rays from the camera to
        :meth:`surface_points_m` first hit anything (nan: no hit)."""
        points = self.surface_points_m(T_base_bowl)
        seen = camera.sees_points(points)
        miss = np.linalg.norm(hits_m - points, axis=1)
        seen &= np.nan_to_num(miss, nan=np.inf) <= self.config.hit_tolerance_m
        n = int(seen.sum())
        fraction = n / len(points)
        if fraction < self.config.min_visible_fraction:
            reason = (
                f"only {fraction:.0%} of the bowl is in view (model of the tracker), need "
                f"{self.config.min_visible_fraction:.0%}: the bowl is out of view or hidden"
            )
            return BowlTrack(False, None, n, float("nan"), reason, time_s)
        return BowlTrack(True, T_base_bowl[:3, 3].copy(), n, 0.0, "", time_s)

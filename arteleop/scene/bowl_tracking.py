"""Find the bowl in one RGB-D frame: colour segmentation, then a fit of the bowl's shape.

The bowl is radially symmetric, so its pose reduces to the position of its bottom centre (x, y, z)
and, where it is left leaning (on a finger, on its rim), the tilt of its axis. Every segmented
point should lie on the bowl's wall, whose cross-section in (radius, height) is known
(:meth:`BowlSpec.profile`); a robust least-squares fit moves the bowl's axis, upright, until the
points sit on that cross-section, then frees its tilt: a tilted bowl fitted upright is placed
centimetres off. The tracker answers "not found", with the
reason, when too few bowl pixels are visible or when the fit does not explain them.
"""

from __future__ import annotations

import colorsys
import math
from dataclasses import dataclass

import cv2
import numpy as np
from numpy.typing import NDArray
from scipy.optimize import least_squares
from scipy.spatial.transform import Rotation

from arteleop.errors import ConfigurationError
from arteleop.scene.bowl import BowlSpec
from arteleop.scene.camera import RGBDFrame
from arteleop.scene.pointcloud import frame_to_point_cloud


@dataclass(frozen=True)
class BowlTrackerConfig:
    """Settings of the bowl tracker.

    Attributes:
        hue_tolerance_deg: Accept pixels within this hue distance of the bowl's colour.
        min_saturation: Minimum HSV saturation (0..1) of bowl pixels; the table is grey.
        min_value: Minimum HSV value (0..1) of bowl pixels; the markers are black.
        min_points: Fewest bowl points, at 640x480, for an answer (scaled with the image area).
        max_rms_m: Largest RMS distance of inlier points to the fitted wall (m).
        min_inlier_fraction: Fraction of points that must lie within 3 * max_rms_m of the wall.
        min_coverage_deg: The points must surround the fitted axis over at least this many
            degrees (in 30-degree sectors). A bowl in full view shows the near side of its outer
            wall and the far side of its inner wall: all the way round. A partly hidden bowl
            shows an arc, which a bowl at many other places fits as well.
        stride: Use every stride-th pixel (1 = all).
        max_fit_points: The fit uses at most this many points, evenly spread over the bowl.
    """

    hue_tolerance_deg: float = 15.0
    min_saturation: float = 0.5
    min_value: float = 0.25
    min_points: int = 300
    max_rms_m: float = 0.006
    min_inlier_fraction: float = 0.7
    min_coverage_deg: float = 270.0
    stride: int = 1
    max_fit_points: int = 800

    def __post_init__(self) -> None:
        if not 0 < self.hue_tolerance_deg < 180 or self.min_points < 3 or self.max_rms_m <= 0:
            raise ConfigurationError(
                "BowlTrackerConfig needs 0 < hue_tolerance_deg < 180, min_points >= 3 and "
                f"max_rms_m > 0; got {self.hue_tolerance_deg}, {self.min_points}, {self.max_rms_m}"
            )


@dataclass(frozen=True)
class BowlTrack:
    """Result of tracking the bowl in one frame.

    Attributes:
        found: Whether the bowl was found. When False, ``position_m`` is None.
        position_m: Bottom centre of the bowl in the base frame (m).
        n_points: Bowl points used.
        rms_m: RMS distance of inlier points to the fitted wall (m).
        reason: Why the bowl was not found (empty when found).
        timestamp_s: Timestamp of the frame.
    """

    found: bool
    position_m: NDArray[np.float64] | None
    n_points: int
    rms_m: float
    reason: str
    timestamp_s: float


class BowlTracker:
    """Tracks a bowl of known shape and colour, upright or tilted."""

    def __init__(self, spec: BowlSpec, config: BowlTrackerConfig | None = None) -> None:
        self.spec = spec
        self.config = config or BowlTrackerConfig()
        profile = spec.profile(12)
        self._seg_a = profile[:-1]  # (M, 2) start of each cross-section segment, (r, h)
        self._seg_d = np.diff(profile, axis=0)
        self._seg_len2 = (self._seg_d**2).sum(-1)
        self._hue_deg = 360.0 * colorsys.rgb_to_hsv(*spec.rgba[:3])[0]

    def segment(self, frame: RGBDFrame) -> NDArray[np.bool_]:
        """(H, W) mask of pixels whose colour matches the bowl's and whose depth is valid."""
        c = self.config
        hsv = cv2.cvtColor(frame.rgb, cv2.COLOR_RGB2HSV_FULL).astype(np.float64)
        hue = hsv[..., 0] * 360.0 / 256.0
        dhue = np.abs((hue - self._hue_deg + 180.0) % 360.0 - 180.0)
        return (
            (dhue <= c.hue_tolerance_deg)
            & (hsv[..., 1] >= 255 * c.min_saturation)
            & (hsv[..., 2] >= 255 * c.min_value)
            & (frame.depth_m > 0)
        )

    def track(
        self, frame: RGBDFrame, table_top_z_m: float, near_m: NDArray[np.float64] | None = None
    ) -> BowlTrack:
        """Estimate the position of the bowl's bottom centre in ``frame``, upright or tilted.

        ``near_m``, the previous estimate (base frame, m), starts the fit there: tracking frame
        to frame converges in a few iterations.
        """
        c = self.config
        mask = self.segment(frame)
        cloud = frame_to_point_cloud(frame, c.stride)
        rows, cols = cloud.pixels[:, 0], cloud.pixels[:, 1]
        pts = cloud.points_m[mask[rows, cols]]
        area_scale = frame.depth_m.size / (640 * 480) / c.stride**2
        needed = max(3, int(c.min_points * area_scale))
        if len(pts) < needed:
            return self._not_found(
                frame,
                len(pts),
                f"only {len(pts)} bowl-coloured points in view, need {needed}: "
                "the bowl is out of view or hidden",
            )
        fit_pts = pts[:: max(1, len(pts) // c.max_fit_points)]
        if near_m is None:
            x0 = np.array([*np.median(pts[:, :2], axis=0), table_top_z_m])
        else:
            x0 = np.asarray(near_m, dtype=np.float64)
        fit = least_squares(
            self._residuals,
            x0,
            jac=self._jacobian,
            args=(fit_pts,),
            loss="soft_l1",
            f_scale=self.spec.wall_thickness_m,
            x_scale=0.01,
        )
        position = fit.x
        tilted = self._tilted(fit.x, fit_pts)
        if tilted is None:
            r = np.abs(self._residuals(fit.x, pts))
        else:
            position = tilted[:3]
            r = np.abs(self._tilted_residuals(tilted, pts))
        inliers = r <= 3 * c.max_rms_m
        rms = float(np.sqrt(np.mean(r[inliers] ** 2))) if inliers.any() else float("inf")
        if inliers.mean() < c.min_inlier_fraction or rms > c.max_rms_m:
            return self._not_found(
                frame,
                len(pts),
                f"the bowl's shape does not fit the points (RMS {rms * 1000:.1f} mm, "
                f"{inliers.mean():.0%} inliers): it may be tipped over, held or partly hidden",
                rms,
            )
        around_deg = coverage_deg(pts[inliers, :2] - position[:2])
        if around_deg < c.min_coverage_deg:
            return self._not_found(
                frame,
                len(pts),
                f"the bowl's points span only {around_deg:.0f} of 360 degrees around its axis, "
                f"need {c.min_coverage_deg:.0f}: it is partly hidden",
                rms,
            )
        return BowlTrack(True, position, len(pts), rms, "", frame.timestamp_s)

    def _residuals(self, x: NDArray[np.float64], pts: NDArray[np.float64]) -> NDArray[np.float64]:
        """Distance (m) of each point to the wall cross-section, for a bowl with bottom centre x."""
        return np.linalg.norm(self._offsets(x, pts)[0], axis=1)

    def _jacobian(self, x: NDArray[np.float64], pts: NDArray[np.float64]) -> NDArray[np.float64]:
        """d residual / d x, (N, 3): the residual is the length of the offset from the nearest
        point of the cross-section, and moving the axis by dx moves each point's (r, h) by
        (-dx . radial, -dz)."""
        offset, radial = self._offsets(x, pts)
        n = offset / np.maximum(np.linalg.norm(offset, axis=1), 1e-12)[:, None]
        return np.column_stack([-n[:, :1] * radial, -n[:, 1]])

    def _offsets(
        self, x: NDArray[np.float64], pts: NDArray[np.float64]
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Each point's (r, h) offset from the nearest point of the cross-section, (N, 2), and
        its unit radial direction in the table's plane, (N, 2)."""
        dxy = pts[:, :2] - x[:2]
        r = np.hypot(dxy[:, 0], dxy[:, 1])
        rh = np.column_stack([r, pts[:, 2] - x[2]])
        radial = dxy / np.maximum(r, 1e-12)[:, None]
        return self._profile_offsets(rh), radial

    def _profile_offsets(self, rh: NDArray[np.float64]) -> NDArray[np.float64]:
        """Each (r, h) point's offset from the nearest point of the cross-section, (N, 2)."""
        rel = rh[:, None, :] - self._seg_a[None, :, :]  # (N, M, 2)
        t = np.clip((rel * self._seg_d).sum(-1) / self._seg_len2, 0.0, 1.0)
        off = rel - t[..., None] * self._seg_d
        nearest = np.einsum("nmk,nmk->nm", off, off).argmin(axis=1)
        return off[np.arange(len(rh)), nearest]

    def _tilted_residuals(
        self, x: NDArray[np.float64], pts: NDArray[np.float64]
    ) -> NDArray[np.float64]:
        """Distance (m) of each point to the wall cross-section, for a bowl with bottom centre
        ``x[:3]`` whose axis is tilted by the rotation vector ``(x[3], x[4], 0)`` (rad)."""
        in_bowl = Rotation.from_rotvec([x[3], x[4], 0.0]).inv().apply(pts - x[:3])
        rh = np.column_stack([np.hypot(in_bowl[:, 0], in_bowl[:, 1]), in_bowl[:, 2]])
        return np.linalg.norm(self._profile_offsets(rh), axis=1)

    def _tilted(
        self, upright: NDArray[np.float64], pts: NDArray[np.float64]
    ) -> NDArray[np.float64] | None:
        """The pose of a bowl left tilted (on the gripper's finger, on its own rim): its bottom
        centre and its axis's tilt (``_tilted_residuals``' five numbers), fitted with the axis
        free from the ``upright`` fit; None if the bowl stands upright
        (tilted less than :data:`MIN_TILT_RAD`) or the tilted fit explains the points no
        better. An upright fit of a bowl tilted by 30 degrees is off by about 4 cm."""
        fit = least_squares(
            self._tilted_residuals, np.append(upright, [0.0, 0.0]), args=(pts,),
            loss="soft_l1", f_scale=self.spec.wall_thickness_m, x_scale=0.01,
        )  # fmt: skip
        if np.hypot(fit.x[3], fit.x[4]) < MIN_TILT_RAD:
            return None
        upright_r = np.abs(self._residuals(upright, pts))
        tilted_r = np.abs(self._tilted_residuals(fit.x, pts))
        return fit.x if np.median(tilted_r) < np.median(upright_r) else None

    @staticmethod
    def _not_found(frame: RGBDFrame, n: int, reason: str, rms: float = float("nan")) -> BowlTrack:
        return BowlTrack(False, None, n, rms, reason, frame.timestamp_s)


SECTOR_DEG = 30.0

MIN_TILT_RAD = math.radians(2.0)
"""A bowl whose fitted axis leans less than this stands upright: the upright fit is kept."""


def coverage_deg(offsets_xy: NDArray[np.float64], min_points: int = 2) -> float:
    """Degrees of azimuth, in ``SECTOR_DEG`` sectors, that hold at least ``min_points`` of the
    given (N, 2) offsets from the bowl's axis."""
    azimuth = np.degrees(np.arctan2(offsets_xy[:, 1], offsets_xy[:, 0]))
    counts = np.histogram(azimuth, bins=round(360 / SECTOR_DEG), range=(-180.0, 180.0))[0]
    return float((counts >= min_points).sum() * SECTOR_DEG)

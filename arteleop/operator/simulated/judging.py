"""One glance's judgements of what a display frame draws: a drawn thing's place against another,
with the precision of what is drawn (:func:`~arteleop.operator.simulated.acuity.judgement_sd`),
combined with the depth aids' judgements where they are drawn, and the fixations each takes.

:class:`Judge` holds what every judgement of one glance shares (the frame, the person, their
errors); :mod:`arteleop.operator.simulated.perception` says which judgements a glance makes.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from arteleop.ar_features import HEIGHT_LABEL_STEP_M, DisplayFrame
from arteleop.operator.simulated.acuity import Judgement, fixations, judgement_sd, reading_sd_m
from arteleop.operator.simulated.mark_memory import MarkMemory
from arteleop.operator.simulated.perceptual_errors import PerceptualErrors

if TYPE_CHECKING:
    from arteleop.operator.simulated.perception import PerceptionParams

Estimate = tuple[NDArray[np.float64], NDArray[np.float64]]
"""A judged point or interval (m) and the covariance the person believes it has (m^2)."""


@dataclass(frozen=True)
class Mark:
    """A mark on the table as judged (m) with its believed covariance (m^2), the fixations it
    took, and whether it came from memory (the display did not draw enough of it)."""

    mark_m: NDArray[np.float64]
    cov: NDArray[np.float64]
    fixations: int
    remembered: bool = False


def shown_gripper_m(view: DisplayFrame) -> NDArray[np.float64]:
    """Where the display shows the gripper (m): the predictive ghost's, where it is on (where
    the commands sent will put it); else the ghost's (where the encoders put it); else the real
    gripper's in the cloud (the camera's registration error moves it)."""
    if view.cues.predictive_ghost:
        predicted = view.predicted
        return view.gripper_m if predicted is None else predicted.gripper_m
    return view.gripper_m if view.cues.ghost else view.in_cloud(view.gripper_m)


class Judge:
    """The judgements of one glance at ``view`` by a person with ``errors``: ``depth_factor``
    scales their depth SD; ``depth_scale`` is how they see a depth interval in the rendered
    scene (1: true), a lasting error they do not know of, so not in the believed covariances;
    ``marks``: where they remember the marks on the table (a fresh memory: none seen yet).
    """

    def __init__(
        self,
        view: DisplayFrame,
        params: PerceptionParams,
        errors: PerceptualErrors,
        depth_factor: float = 1.0,
        depth_scale: float = 1.0,
        marks: MarkMemory | None = None,
    ) -> None:
        self.view = view
        self.params = params
        self.errors = errors
        self.depth_factor = depth_factor
        self.depth_scale = depth_scale
        self.shown_gripper = shown_gripper_m(view)
        predicted = view.shown_predicted
        self.lead_m = np.zeros(3) if predicted is None else predicted.gripper_m - view.gripper_m
        """How far the predictive ghost leads the frame's own arm (m), which the person sees."""
        self.cloud_grain = view.cloud_spacing_rad or 0.0  # batch frames carry no cloud
        self.marks = marks or MarkMemory(params)

    def mark(
        self, name: str, drawn: float, against_m: NDArray[np.float64], judge: Callable[[], Mark]
    ) -> Mark:
        """The mark ``name`` on the table, of which the display draws the share ``drawn``:
        ``judge()``'s judgement of it where enough is drawn to find its centre, remembered;
        else where it is remembered, looking there and at what it is judged against
        (``against_m``). A mark never seen in the trial is judged where it is drawn: the
        person saw the scene before the trial began."""
        view = self.view
        if drawn < self.params.mark_drawn_min:
            recalled = self.marks.recall(name, view.time_s, view.viewpoint_m, self.errors)
            if recalled is not None:
                remembered, cov = recalled
                return Mark(remembered, cov, self.fixated(remembered, against_m), True)
        seen = judge()
        self.marks.saw(name, view.time_s, seen.mark_m, seen.cov)
        return seen

    def fixated(self, *seen_m: NDArray[np.float64], read_m: tuple = ()) -> int:
        """The fixations a judgement of ``seen_m`` that reads the labels at ``read_m`` takes."""
        p = self.params
        return fixations(seen_m, read_m, self.view.viewpoint_m, p.parafovea_rad, p.fovea_rad)

    def precision(
        self, point: NDArray[np.float64], interval_m: float, grain_rad: float
    ) -> Judgement:
        """The SDs of judging an interval of ``interval_m`` (m) at ``point``, drawn at
        ``grain_rad``, this person's depth factor applied."""
        eye = float(np.linalg.norm(point - self.view.viewpoint_m))
        sd = judgement_sd(interval_m, eye, grain_rad, self.params.display, self.params.acuities)
        return Judgement(sd.across_sd_m, sd.depth_sd_m * self.depth_factor)

    def seen(
        self,
        stream: str,
        point: NDArray[np.float64],
        reference: NDArray[np.float64],
        grain_rad: float,
        along_sd: float | None = None,
        axis: NDArray[np.float64] | None = None,
        stretched: bool = True,
    ) -> Estimate:
        """``point`` judged relative to ``reference`` (both drawn at ``grain_rad``) in one more
        glance: the judgement and its believed covariance (fresh noise, which looking averages).

        Along the line of sight depth is seen in stereo and the person's depth scale stretches
        the interval (once per pair: not ``stretched`` for the other of a pair judged against
        each other); with ``axis`` (a drawn line from ``point`` to ``reference``) the interval
        along it is read off a label with SD ``along_sd`` instead."""
        d = point - self.view.viewpoint_m
        d = d / np.linalg.norm(d)
        interval = point - reference
        sd = self.precision(point, float(np.linalg.norm(interval)), grain_rad)
        z = self.errors.draw_fresh(stream, 3)
        glances = self.errors.glances(stream)
        if axis is None:
            a, a_sd = d, sd.depth_sd_m
            lasting = (self.depth_scale - 1.0) * (interval @ d) * d * stretched
        else:
            a, a_sd = axis / np.linalg.norm(axis), float(along_sd)
            lasting = np.zeros(3)
        across = z[1:] @ _orthonormal(a) * sd.across_sd_m
        along = np.outer(a, a)
        cov = (a_sd**2 * along + sd.across_sd_m**2 * (np.eye(3) - along)) / glances
        return point + a * (z[0] * a_sd) + across + lasting, cov

    def held_level(
        self,
        stream: str,
        point: NDArray[np.float64],
        on_line_m: NDArray[np.float64],
        grain_rad: float,
        ahead_m: NDArray[np.float64],
    ) -> Estimate:
        """``point`` judged against ``on_line_m``, where the depth aids' drop line passes its
        height (the ring, for a mark on the table), taking both to be level: the judgement held
        to their horizontal plane, the estimate nearest in its believed error. The line hangs
        from the frame's arm, so that is ``point`` relative to the arm in the plane; returned
        relative to the gripper the judgement is about, ``ahead_m`` (m) ahead of the arm (the
        predictive ghost's lead, or none), with its information in the plane (inverse
        covariance, m^-2; none about the height)."""
        on_line, line_cov = self.seen(stream, point, on_line_m, grain_rad)
        line_info = np.linalg.inv(line_cov)
        plane = np.eye(3)[:, :2]
        info_2 = plane.T @ line_info @ plane
        level = np.linalg.solve(info_2, plane.T @ line_info @ (on_line - on_line_m))
        return plane @ level - ahead_m, plane @ info_2 @ plane.T

    def with_aids(
        self,
        stream: str,
        point: NDArray[np.float64],
        judged: NDArray[np.float64],
        cov: NDArray[np.float64],
        grain_rad: float,
        read_height: bool,
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], int]:
        """``point``, a mark on the table, ``judged`` against the shown gripper with believed
        covariance ``cov``, combined with its judgement against the depth aids' ring
        (:meth:`held_level`) and (``read_height``) the gripper's height read off the label.
        The combined judgement, its covariance, and the fixations it takes with the shown
        gripper: the ring seen, the label read."""
        view, shown = self.view, self.shown_gripper
        aimed = (point, shown)
        if not view.depth_aids:
            return judged, cov, self.fixated(*aimed)
        ring = view.ring_m()
        aided, aided_info = self.held_level(
            stream + " on the ring", point, ring, grain_rad, self.lead_m
        )
        read_m: tuple[NDArray[np.float64], ...] = ()
        if read_height:  # the mark on the table, the gripper the label's height above it
            aided[2] = -view.height_shown_m() - self.lead_m[2]
            aided_info[2, 2] += 1.0 / reading_sd_m(HEIGHT_LABEL_STEP_M) ** 2
            read_m = (view.height_label_m(),)
        relative, combined_cov = combined(judged - shown, cov, aided, aided_info)
        return shown + relative, combined_cov, self.fixated(*aimed, ring, read_m=read_m)

    def centre(self, point: NDArray[np.float64], grain_rad: float) -> Estimate:
        """The target circle's centre found by eye at ``point``, bisecting the circle drawn at
        ``grain_rad``, a radius from its rim: the error and its believed covariance."""
        sd = self.precision(point, self.view.target_radius_m, grain_rad)
        return self.planar("centring", sd.across_sd_m)

    def planar(self, stream: str, sd: float) -> Estimate:
        """An error in the table's plane with ``sd`` per axis, and its believed covariance."""
        z = self.errors.draw_fresh(stream, 2) * sd
        glances = self.errors.glances(stream)
        return np.append(z, 0.0), np.diag([sd**2, sd**2, 0.0]) / glances


def combined(
    relative: NDArray[np.float64],
    cov: NDArray[np.float64],
    aided: NDArray[np.float64],
    aided_info: NDArray[np.float64],
) -> Estimate:
    """Two judgements of one interval (m), believed with covariance ``cov`` and information
    ``aided_info``, weighed by their information: the combination and its covariance."""
    combined_cov = np.linalg.inv(np.linalg.inv(cov) + aided_info)
    return combined_cov @ (np.linalg.solve(cov, relative) + aided_info @ aided), combined_cov


def _orthonormal(axis: NDArray[np.float64]) -> NDArray[np.float64]:
    """(2, 3) two unit vectors perpendicular to the unit ``axis`` and to each other."""
    helper = np.array([1.0, 0.0, 0.0]) if abs(axis[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    u = np.cross(axis, helper)
    u /= np.linalg.norm(u)
    return np.stack([u, np.cross(axis, u)])

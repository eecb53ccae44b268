"""What the operator sees on the display, and how well: judgements of what is drawn.

The operator never reads the simulator's state. At each glance it judges the gripper, the bowl
and the target from what the display frame shows. Every judgement is of a drawn thing's place
relative to another, and its precision is one function of what is drawn
(:func:`~arteleop.operator.acuity.judgement_sd`: the interval judged, the grain it is drawn at,
the display's stereo; no layer has a precision of its own). What each layer changes is what
there is to judge:

- the bowl is seen only when the camera shows it (``DisplayFrame.bowl_m``); hidden by the arm,
  it is not seen, and the operator relies on memory (:class:`BowlMemory`);
- in the point cloud the gripper is judged against the bowl's grasp point, in stereo depth;
- the beam draws that interval at the display's own grain; the distance bar's label gives its
  length, read to the label's last digit, so depth along it no longer comes from stereo;
- the target mesh turns placement into a coincidence judgement (an interval near zero): of the
  bowl with the mesh, or, while the arm hides the bowl in hand, of the gripper with where it
  would hold the mesh (and then the bowl's place in the hand adds its own uncertainty);
  without it the marker's centre is found by bisecting its circle;
- the ghost shows the arm when the camera cannot; without it, an unseen gripper is estimated
  from the operator's own arm (proprioception);
- what the point cloud shows is displaced by the camera's registration error
  (``DisplayFrame.T_cloud_true``), the AR layers are not;
- the depth aids (``DisplayFrame.depth_aids``, in every condition of a study or in none) give a
  second judgement of a mark on the table against the gripper: the ring at the drop line's foot
  against the mark, both on the table, so the judgement is held to its plane; and, where the
  height matters, the gripper's height read off the label. Above the rim, the line passes the
  rim's height where the gripper, lowered, would be: the grasp point against that point of the
  line, level. A person combines each with the judgement without the aids, each by its
  precision (Ernst & Banks 2002).

A judgement of the display errs afresh at each glance (a longer look averages it) and, along the
line of sight, by the person's lasting depth scale, which the person does not know of. A
proprioceptive judgement has a lasting bias per person (:class:`PerceptualErrors`). The operator
knows how precise a judgement is (its covariance, :class:`Perceived`), not its own lasting error.
"""

from __future__ import annotations

import math
import zlib
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from arteleop.ar_features import (
    DISTANCE_LABEL_STEP_M,
    HEIGHT_LABEL_STEP_M,
    DisplayFrame,
)
from arteleop.checks import Bounds, check_fields
from arteleop.operator.acuity import (
    Acuities,
    DisplayGeometry,
    Judgement,
    fixations,
    judgement_sd,
    reading_sd_m,
)


@dataclass(frozen=True)
class PerceptionParams:
    """What sets a judgement's precision: the display, published acuities, and how a person's
    errors split.

    Attributes:
        display: The display the operator looks through.
        acuities: Published acuities; every judgement of what the display draws takes its
            precision from :func:`~arteleop.operator.acuity.judgement_sd` of these two.
        proprioception_sd_m: Estimating an unseen gripper from one's own arm, per axis (m):
            not a judgement of the display.
        bias_share: Share of a proprioceptive judgement's variance that lasts (the person's
            bias); the rest is fresh at every glance. Judgements of the display are fresh at
            every glance; their lasting error is the person's depth scale (a trait).
        parafovea_rad: How far from a fixation where a thing is can be seen (rad).
        fovea_rad: How far from a fixation a label can be read (rad). A judgement needs a
            fixation for each label and each thing no other fixation covers
            (:func:`~arteleop.operator.acuity.fixations`).
        eye_movement_s: What each fixation after a glance's first adds to its time (s): an
            eye movement and the fixation it ends in.
    """

    display: DisplayGeometry = field(default_factory=DisplayGeometry)
    acuities: Acuities = field(default_factory=Acuities)
    proprioception_sd_m: float = 0.03
    bias_share: float = 0.5
    parafovea_rad: float = math.radians(5.0)
    fovea_rad: float = math.radians(1.0)
    eye_movement_s: float = 0.23

    def __post_init__(self) -> None:
        check_fields(self, {
            "bias_share": Bounds(0, 1),
            "parafovea_rad": Bounds(0, 0.5, "rad", above=True),
            "fovea_rad": Bounds(0, 0.5, "rad", above=True),
            "eye_movement_s": Bounds(0, 1, "s"),
        })  # fmt: skip

    def belief_scale(self, glances: int) -> float:
        """The variance of a judgement averaged over ``glances`` glances, as a share of one
        glance's: the bias stays, the fresh noise averages."""
        return self.bias_share + (1.0 - self.bias_share) / max(glances, 1)


class PerceptualErrors:
    """A person's judgement errors in standard units, one stream per judgement.

    A stream's bias is drawn once from ``bias_seed`` and the stream's name, so a person errs the
    same way in every trial; each glance adds fresh noise from ``rng``, averaged over the look's
    glances (:meth:`new_look` starts a look).
    """

    def __init__(self, rng: np.random.Generator, bias_seed: int, bias_share: float) -> None:
        self._rng = rng
        self._seed = bias_seed
        self._bias_sd, self._fresh_sd = np.sqrt(bias_share), np.sqrt(1.0 - bias_share)
        self._bias: dict[str, NDArray[np.float64]] = {}
        self._sums: dict[str, tuple[int, NDArray[np.float64]]] = {}

    def new_look(self) -> None:
        """Forget the fresh noise of the last look."""
        self._sums.clear()

    def draw(self, stream: str, size: int) -> NDArray[np.float64]:
        """One more glance at ``stream``: the bias plus the mean of this look's fresh noise,
        weighted by the split of a glance's variance."""
        fresh = self.draw_fresh(stream, size)
        return self._bias_sd * self.bias(stream, size) + self._fresh_sd * fresh

    def draw_fresh(self, stream: str, size: int) -> NDArray[np.float64]:
        """One more glance at ``stream`` without a lasting part: the mean of this look's
        fresh noise (standard units per glance)."""
        n, total = self._sums.get(stream, (0, np.zeros(size)))
        n, total = n + 1, total + self._rng.normal(0.0, 1.0, size)
        self._sums[stream] = (n, total)
        return total / n

    def bias(self, stream: str, size: int) -> NDArray[np.float64]:
        """The person's lasting bias of ``stream`` (standard units)."""
        bias = self._bias.get(stream)
        if bias is None:
            stream_rng = np.random.default_rng([self._seed, zlib.crc32(stream.encode())])
            bias = self._bias[stream] = stream_rng.normal(0.0, 1.0, size)
        return bias

    def glances(self, stream: str) -> int:
        """Glances at ``stream`` in this look."""
        return self._sums.get(stream, (0, None))[0]


@dataclass(frozen=True)
class Perceived:
    """The operator's judgements at one glance, base frame (m); ``bowl_m`` is None when the
    display does not show the bowl.

    ``grasp_cov`` is the covariance (3, 3; m^2) of the judged gripper relative to the bowl (or,
    without a bowl in view, to where the operator remembers it); ``placement_cov`` that of the
    judged target relative to the bowl (or the gripper, see ``placed_by_gripper``). Both are
    what the operator believes of its own precision: the bias's variance and the look's
    averaged noise.

    Attributes:
        gripper_seen: The display shows the gripper (in the cloud or as the ghost).
        closure_known: The display shows whether the gripper is closed.
        placed_by_gripper: The placement was judged from the gripper (the bowl in hand hidden):
            the bowl's place in the hand adds its own uncertainty.
        lead_m: How far ahead of the frame's own arm the gripper judged is (m): the predictive
            ghost's lead, zero without it. The bowl is seen in the frame, a round trip old: a
            bowl carried by the hand is that much behind where the judged gripper carries it.
        grasp_fixations: The fixations the gripper's judgement against the bowl took: one
            per label read and per drawn thing no other fixation covers
            (:func:`~arteleop.operator.acuity.fixations`).
        placement_fixations: ...and the placement's judgement.
        start_m: Where the start is judged, at the centre of its cross; None unless the task
            aims the gripper and the display gives the start.
        start_cov: (3, 3) its believed covariance relative to the judged gripper (m^2).
        start_fixations: The fixations its judgement took.
    """

    gripper_m: NDArray[np.float64]
    bowl_m: NDArray[np.float64] | None
    target_m: NDArray[np.float64]
    gripper_seen: bool
    closure_known: bool
    grasp_cov: NDArray[np.float64]
    placement_cov: NDArray[np.float64]
    placed_by_gripper: bool
    lead_m: NDArray[np.float64] = field(default_factory=lambda: np.zeros(3))
    grasp_fixations: int = 1
    placement_fixations: int = 1
    start_m: NDArray[np.float64] | None = None
    start_cov: NDArray[np.float64] | None = None
    start_fixations: int = 1


def shown_gripper_m(view: DisplayFrame) -> NDArray[np.float64]:
    """Where the display shows the gripper (m): the predictive ghost's, where it is on (where
    the commands sent will put it); else the ghost's (where the encoders put it); else the real
    gripper's in the cloud (the camera's registration error moves it)."""
    if view.cues.predictive_ghost:
        predicted = view.predicted
        return view.gripper_m if predicted is None else predicted.gripper_m
    return view.gripper_m if view.cues.ghost else view.in_cloud(view.gripper_m)


def perceive(
    view: DisplayFrame,
    params: PerceptionParams,
    errors: PerceptualErrors,
    depth_factor: float = 1.0,
    depth_scale: float = 1.0,
    aims_gripper: bool = False,
) -> Perceived:
    """One glance at the display frame ``view``, averaged with this look's earlier glances.

    Every judgement is of a drawn thing's place relative to another, with the precision
    :func:`judgement_sd` gives for what is drawn: the interval between them, their grain and
    the display's stereo. ``depth_factor`` scales the person's depth SD; ``depth_scale`` is how
    the person sees a depth interval in the rendered scene (1: true), a lasting error the person
    does not know of, so it is not in the believed covariances. Where the task ``aims_gripper``
    (pointing), the target is judged against the gripper shown over it, not the bowl, and so is
    the start (``view.start_m``)."""
    cues = view.cues
    gripper_seen = view.gripper_in_camera or cues.ghost or cues.predictive_ghost
    shown_gripper = shown_gripper_m(view)
    predicted = view.shown_predicted
    # How far the predictive ghost leads the frame's own arm (m), which the person sees.
    lead_m = np.zeros(3) if predicted is None else predicted.gripper_m - view.gripper_m
    cloud_grain = view.cloud_spacing_rad or 0.0  # batch frames carry no cloud: the display's

    def fixated(*seen_m: NDArray[np.float64], read_m: tuple = ()) -> int:
        return fixations(seen_m, read_m, view.viewpoint_m, params.parafovea_rad, params.fovea_rad)

    def precision(point: NDArray[np.float64], interval_m: float, grain_rad: float) -> Judgement:
        eye = float(np.linalg.norm(point - view.viewpoint_m))
        sd = judgement_sd(interval_m, eye, grain_rad, params.display, params.acuities)
        return Judgement(sd.across_sd_m, sd.depth_sd_m * depth_factor)

    def seen(
        stream: str,
        point: NDArray[np.float64],
        reference: NDArray[np.float64],
        grain_rad: float,
        along_sd: float | None = None,
        axis: NDArray[np.float64] | None = None,
        stretched: bool = True,
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """``point`` judged relative to ``reference`` (both drawn at ``grain_rad``) in one more
        glance: the judgement and its believed covariance (fresh noise, which looking averages).

        Along the line of sight depth is seen in stereo and the person's depth scale stretches
        the interval (once per pair: not ``stretched`` for the other of a pair judged against
        each other); with ``axis`` (a drawn line from ``point`` to ``reference``) the interval
        along it is read off a label with SD ``along_sd`` instead."""
        d = point - view.viewpoint_m
        d = d / np.linalg.norm(d)
        interval = point - reference
        sd = precision(point, float(np.linalg.norm(interval)), grain_rad)
        z = errors.draw_fresh(stream, 3)
        glances = errors.glances(stream)
        if axis is None:
            a, a_sd = d, sd.depth_sd_m
            lasting = (depth_scale - 1.0) * (interval @ d) * d * stretched
        else:
            a, a_sd = axis / np.linalg.norm(axis), float(along_sd)
            lasting = np.zeros(3)
        across = z[1:] @ _orthonormal(a) * sd.across_sd_m
        along = np.outer(a, a)
        cov = (a_sd**2 * along + sd.across_sd_m**2 * (np.eye(3) - along)) / glances
        return point + a * (z[0] * a_sd) + across + lasting, cov

    def held_level(
        stream: str,
        point: NDArray[np.float64],
        on_line_m: NDArray[np.float64],
        grain_rad: float,
        ahead_m: NDArray[np.float64],
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """``point`` judged against ``on_line_m``, where the depth aids' drop line passes its
        height (the ring, for a mark on the table), taking both to be level: the judgement held
        to their horizontal plane, the estimate nearest in its believed error. The line hangs
        from the frame's arm, so that is ``point`` relative to the arm in the plane; returned
        relative to the gripper the judgement is about, ``ahead_m`` (m) ahead of the arm (the
        predictive ghost's lead, or none), with its information in the plane (inverse
        covariance, m^-2; none about the height)."""
        on_line, line_cov = seen(stream, point, on_line_m, grain_rad)
        line_info = np.linalg.inv(line_cov)
        plane = np.eye(3)[:, :2]
        info_2 = plane.T @ line_info @ plane
        level = np.linalg.solve(info_2, plane.T @ line_info @ (on_line - on_line_m))
        return plane @ level - ahead_m, plane @ info_2 @ plane.T

    def combined(
        relative: NDArray[np.float64],
        cov: NDArray[np.float64],
        aided: NDArray[np.float64],
        aided_info: NDArray[np.float64],
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Two judgements of one interval (m), believed with covariance ``cov`` and information
        ``aided_info``, weighed by their information: the combination and its covariance."""
        combined_cov = np.linalg.inv(np.linalg.inv(cov) + aided_info)
        return combined_cov @ (np.linalg.solve(cov, relative) + aided_info @ aided), combined_cov

    def with_aids(
        stream: str,
        point: NDArray[np.float64],
        judged: NDArray[np.float64],
        cov: NDArray[np.float64],
        grain_rad: float,
        read_height: bool,
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], int]:
        """``point``, a mark on the table, ``judged`` against the shown gripper with believed
        covariance ``cov``, combined with its judgement against the depth aids' ring
        (:func:`held_level`) and (``read_height``) the gripper's height read off the label.
        The combined judgement, its covariance, and the fixations it takes with the shown
        gripper: the ring seen, the label read."""
        aimed = (point, shown_gripper)
        if not view.depth_aids:
            return judged, cov, fixated(*aimed)
        ring = view.ring_m()
        aided, aided_info = held_level(stream + " on the ring", point, ring, grain_rad, lead_m)
        read_m: tuple[NDArray[np.float64], ...] = ()
        if read_height:  # the mark on the table, the gripper the label's height above it
            aided[2] = -view.height_shown_m() - lead_m[2]
            aided_info[2, 2] += 1.0 / reading_sd_m(HEIGHT_LABEL_STEP_M) ** 2
            read_m = (view.height_label_m(),)
        relative, combined_cov = combined(judged - shown_gripper, cov, aided, aided_info)
        return shown_gripper + relative, combined_cov, fixated(*aimed, ring, read_m=read_m)

    def centre(
        point: NDArray[np.float64], grain_rad: float
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """The target circle's centre found by eye at ``point``, bisecting the circle drawn at
        ``grain_rad``, a radius from its rim: the error and its believed covariance."""
        sd = precision(point, view.target_radius_m, grain_rad)
        return planar("centring", sd.across_sd_m)

    def planar(stream: str, sd: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """An error in the table's plane with ``sd`` per axis, and its believed covariance."""
        z = errors.draw_fresh(stream, 2) * sd
        glances = errors.glances(stream)
        return np.append(z, 0.0), np.diag([sd**2, sd**2, 0.0]) / glances

    tracked = view.bowl_m
    grasp = view.grasp_point_m()  # what the beam and the distance bar draw
    reference = grasp if grasp is not None else view.target_m
    bowl = bowl_cov = None
    if tracked is not None:
        bowl, bowl_cov = seen("bowl", tracked, view.target_m, cloud_grain)
    if gripper_seen and grasp is not None and tracked is not None and bowl is not None:
        # Judged relative to the bowl. The beam draws the gripper-to-grasp interval with the
        # display's grain; the bar's label gives its length: both show nothing while the bowl
        # is not tracked.
        grain = params.display.pixel_rad if cues.beam else cloud_grain
        beam = view.gripper_m - grasp
        read_m: tuple[NDArray[np.float64], ...] = ()
        ahead = np.zeros(3)  # the beam and the bar hang from the frame's arm, as the line does
        if cues.distance_bar and np.linalg.norm(beam) > 1e-6:
            reading = reading_sd_m(DISTANCE_LABEL_STEP_M)
            judged, grasp_cov = seen("gripper", view.gripper_m, grasp, grain, reading, beam)
            seen_m = (view.gripper_m, grasp)
            read_m = (view.distance_label_m(),)
        elif cues.beam:
            judged, grasp_cov = seen("gripper", view.gripper_m, grasp, grain)
            seen_m = (view.gripper_m, grasp)
        else:
            judged, grasp_cov = seen("gripper", shown_gripper, grasp, grain)
            seen_m = (shown_gripper, grasp)
            ahead = lead_m
        if view.depth_aids and view.gripper_m[2] >= grasp[2]:
            # The drop line passes the rim's height where the gripper, lowered, would be: the
            # rim against that point of the line, both level.
            on_line = view.drop_line_at_m(float(grasp[2]))
            aided, aided_info = held_level("grasp on the line", grasp, on_line, grain, ahead)
            relative, grasp_cov = combined(grasp - judged, grasp_cov, aided, aided_info)
            judged = grasp - relative
            seen_m += (on_line,)
        grasp_fixations = fixated(*seen_m, read_m=read_m)
        gripper = bowl + judged - tracked
        gripper_cov = grasp_cov
    elif gripper_seen:  # against a remembered bowl: seen apart, in other glances
        # The marker is judged against it below: their interval is stretched there.
        gripper, gripper_cov = seen(
            "gripper", shown_gripper, reference, cloud_grain, stretched=False
        )
        grasp_cov = 2 * gripper_cov
        grasp_fixations = 1
    else:
        z = errors.draw("proprioception", 3) * params.proprioception_sd_m
        gripper = view.gripper_m + z
        scale = params.belief_scale(errors.glances("proprioception"))
        grasp_cov = np.eye(3) * params.proprioception_sd_m**2 * scale
        gripper_cov = grasp_cov
        grasp_fixations = 1  # the bowl, the arm felt
        if bowl_cov is not None:
            grasp_cov = grasp_cov + bowl_cov
    placed_by_gripper = False
    # The target as drawn: the mesh where the AR layers put it, or the marker in the cloud.
    mark_point = view.target_m if cues.target_mesh else view.in_cloud(view.target_m)
    if aims_gripper and gripper_seen:
        # The mark against the gripper over it.
        grain = params.display.pixel_rad if cues.target_mesh else cloud_grain
        mark, mark_cov = seen("target", mark_point, shown_gripper, grain)
        mark, mark_cov, placement_fixations = with_aids(
            "target", mark_point, mark, mark_cov, grain, read_height=False
        )
        centring, centring_cov = centre(mark_point, grain)
        target = gripper + mark - shown_gripper + centring
        placement_cov = mark_cov + centring_cov
        placed_by_gripper = True
    elif cues.target_mesh and bowl is not None and tracked is not None:
        # Coincidence of the real and the virtual bowl: their offset, at the mesh's grain.
        offset_m = float(np.linalg.norm((tracked - view.target_m)[:2]))
        sd = precision(view.target_m, offset_m, max(cloud_grain, params.display.pixel_rad))
        offset, placement_cov = planar("coincidence", sd.across_sd_m)
        target = bowl + view.target_m - tracked + offset
        placement_fixations = fixated(view.target_m, tracked)
    elif cues.target_mesh and gripper_seen:
        # The bowl in hand is hidden (the arm is over it): the gripper is put where it would
        # hold the virtual bowl, judged against the mesh beside it, a grasp radius away.
        sd = precision(view.target_m, view.grasp_radius_m, params.display.pixel_rad)
        offset, placement_cov = planar("coincidence", sd.across_sd_m)
        target = gripper + view.target_m - shown_gripper + offset
        placed_by_gripper = True
        placement_fixations = fixated(view.target_m, shown_gripper)
    else:
        # The marker is drawn in the cloud (or, as a mesh with nothing to coincide with, over
        # it) and centred on by eye: its centre bisects the circle, a radius from its rim.
        # Against the bowl, their interval was stretched in the bowl's judgement.
        against = bowl if bowl is not None else shown_gripper
        marker, marker_cov = seen(
            "target", mark_point, against, cloud_grain, stretched=bowl is None
        )
        placement_fixations = fixated(mark_point, against)
        if bowl is None and gripper_seen:
            marker, marker_cov, placement_fixations = with_aids(
                "target", mark_point, marker, marker_cov, cloud_grain, read_height=False
            )
        centring, centring_cov = centre(mark_point, cloud_grain)
        target = marker + centring
        placement_cov = marker_cov + centring_cov
        if bowl_cov is not None:
            placement_cov = placement_cov + bowl_cov
        else:
            placement_cov = placement_cov + gripper_cov
            placed_by_gripper = True
    start = start_cov = None
    start_fixations = 1
    if aims_gripper and view.start_m is not None:
        # The start cross, drawn in the cloud: its centre is where its arms cross, so there is
        # no circle to bisect. Judged against the gripper over it; while the gripper is not
        # shown, against what is (the gripper then felt, not seen).
        cross = view.in_cloud(view.start_m)
        if gripper_seen:
            mark, start_cov = seen("start", cross, shown_gripper, cloud_grain)
            mark, start_cov, start_fixations = with_aids(
                "start", cross, mark, start_cov, cloud_grain, read_height=True
            )
            start = gripper + mark - shown_gripper
        else:
            against = tracked if tracked is not None else mark_point
            start, mark_cov = seen("start", cross, against, cloud_grain)
            start_cov = mark_cov + grasp_cov
            start_fixations = fixated(cross, against)
    closure_known = gripper_seen or cues.grip_bar
    return Perceived(
        gripper, bowl, target, gripper_seen, closure_known, grasp_cov, placement_cov,
        placed_by_gripper, lead_m, grasp_fixations, placement_fixations, start, start_cov,
        start_fixations,
    )  # fmt: skip


def _orthonormal(axis: NDArray[np.float64]) -> NDArray[np.float64]:
    """(2, 3) two unit vectors perpendicular to the unit ``axis`` and to each other."""
    helper = np.array([1.0, 0.0, 0.0]) if abs(axis[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    u = np.cross(axis, helper)
    u /= np.linalg.norm(u)
    return np.stack([u, np.cross(axis, u)])


class BowlMemory:
    """Where the operator believes the bowl is: where a look last showed it, and while it is
    held, where it sits relative to the gripper (it moves with the hand), with the covariance
    (m^2) of that judgement from the grasp."""

    def __init__(self) -> None:
        self._last_seen_m: NDArray[np.float64] | None = None
        self._in_hand_m: NDArray[np.float64] | None = None
        self.in_hand_cov = np.zeros((3, 3))

    def bowl_m(self, seen: Perceived) -> NDArray[np.float64] | None:
        """The bowl after a look: as seen when shown, else as remembered; None before it was
        ever seen."""
        if seen.bowl_m is not None:
            # Held, it is where the judged gripper carries it, ahead of the frame by the lead.
            present = seen.bowl_m + seen.lead_m if self._in_hand_m is not None else seen.bowl_m
            self._last_seen_m = present
            return present
        if self._in_hand_m is not None:
            return seen.gripper_m + self._in_hand_m
        return self._last_seen_m

    @property
    def holding(self) -> bool:
        return self._in_hand_m is not None

    def grasp(self, seen: Perceived, bowl_m: NDArray[np.float64] | None) -> None:
        """The operator has closed the gripper on the bowl believed at ``bowl_m``; the bowl's
        place in the hand is as uncertain as the grasp's judgement was."""
        self._in_hand_m = None if bowl_m is None else bowl_m - seen.gripper_m
        self.in_hand_cov = seen.grasp_cov.copy()

    def release(self) -> None:
        self._in_hand_m = None
        self.in_hand_cov = np.zeros((3, 3))

    def left_behind(self, seen: Perceived, drop_m: float = 0.07) -> bool:
        """A look shows the bowl held a moment ago more than ``drop_m`` below where the hand
        should carry it: the grasp missed and the bowl stayed on the table. (Judged in height:
        a held bowl tilts and the estimates err by centimetres, but a lift is 15 cm.)"""
        if seen.bowl_m is None or self._in_hand_m is None:
            return False
        # Compared within the frame the bowl is seen in: its own gripper, not the lead's.
        expected = seen.gripper_m - seen.lead_m + self._in_hand_m
        return bool(expected[2] - seen.bowl_m[2] > drop_m)

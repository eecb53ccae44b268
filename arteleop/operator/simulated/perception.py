"""What the operator sees on the display, and how well: judgements of what is drawn.

The operator never reads the simulator's state. At each glance it judges the gripper, the bowl
and the target from what the display frame shows. Every judgement is of a drawn thing's place
relative to another, and its precision is one function of what is drawn
(:func:`~arteleop.operator.simulated.acuity.judgement_sd`: the interval judged, the grain it is
drawn at, the display's stereo; no layer has a precision of its own). What each layer changes is
what there is to judge:

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
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from arteleop.ar_features import DISTANCE_LABEL_STEP_M, DisplayFrame
from arteleop.checks import Bounds, check_fields
from arteleop.operator.simulated.acuity import Acuities, DisplayGeometry, reading_sd_m
from arteleop.operator.simulated.judging import Judge, Mark, combined, shown_gripper_m
from arteleop.operator.simulated.mark_judging import MARK_JUDGEMENTS, judgeable_marks
from arteleop.operator.simulated.mark_memory import MarkMemory
from arteleop.operator.simulated.perceptual_errors import PerceptualErrors

__all__ = [
    "GraspJudgement",
    "Perceived",
    "PerceptionParams",
    "PlacementJudgement",
    "judge_grasp",
    "judge_placement",
    "judgeable_marks",
    "perceive",
    "shown_gripper_m",
]


@dataclass(frozen=True)
class PerceptionParams:
    """What sets a judgement's precision: the display, published acuities, and how a person's
    errors split.

    Attributes:
        display: The display the operator looks through.
        acuities: Published acuities; every judgement of what the display draws takes its
            precision from :func:`~arteleop.operator.simulated.acuity.judgement_sd` of these two.
        proprioception_sd_m: Estimating an unseen gripper from one's own arm, per axis (m):
            not a judgement of the display.
        bias_share: Share of a proprioceptive judgement's variance that lasts (the person's
            bias); the rest is fresh at every glance. Judgements of the display are fresh at
            every glance; their lasting error is the person's depth scale (a trait).
        parafovea_rad: How far from a fixation where a thing is can be seen (rad).
        fovea_rad: How far from a fixation a label can be read (rad). A judgement needs a
            fixation for each label and each thing no other fixation covers
            (:func:`~arteleop.operator.simulated.acuity.fixations`).
        eye_movement_s: What each fixation after a glance's first adds to its time (s): an
            eye movement and the fixation it ends in.
        mark_drawn_min: The share of a mark's line (the target circle, the start cross) the
            display must draw for the mark to be judged where it is; less, and it is placed
            from memory (:class:`~arteleop.operator.simulated.mark_memory.MarkMemory`).
        memory_drift_rad: How far a remembered mark's place drifts in its first second
            unseen, SD per axis in the table's plane, as an angle at the eye (rad); the drift's
            variance grows in proportion to the time unseen.
        memory_plateau_s: How long that drift grows (s).
    """

    display: DisplayGeometry = field(default_factory=DisplayGeometry)
    acuities: Acuities = field(default_factory=Acuities)
    proprioception_sd_m: float = 0.03
    bias_share: float = 0.5
    parafovea_rad: float = math.radians(5.0)
    fovea_rad: float = math.radians(1.0)
    eye_movement_s: float = 0.23
    mark_drawn_min: float = 0.5
    memory_drift_rad: float = math.radians(0.1)
    memory_plateau_s: float = 20.0

    def __post_init__(self) -> None:
        check_fields(self, {
            "bias_share": Bounds(0, 1),
            "mark_drawn_min": Bounds(0, 1, "a share of the mark's line"),
            "memory_drift_rad": Bounds(0, 0.1, "rad"),
            "memory_plateau_s": Bounds(0, 600, "s"),
            "parafovea_rad": Bounds(0, 0.5, "rad", above=True),
            "fovea_rad": Bounds(0, 0.5, "rad", above=True),
            "eye_movement_s": Bounds(0, 1, "s"),
        })  # fmt: skip

    def belief_scale(self, glances: int) -> float:
        """The variance of a judgement averaged over ``glances`` glances, as a share of one
        glance's: the bias stays, the fresh noise averages."""
        return self.bias_share + (1.0 - self.bias_share) / max(glances, 1)


@dataclass(frozen=True)
class Perceived:
    """The operator's judgements at one glance, base frame (m); ``bowl_m`` is None when the
    display does not show the bowl.

    ``gripper_cov`` is the covariance (3, 3; m^2) of the judged gripper relative to the bowl
    (or, without a bowl in view, to where the operator remembers it); ``target_cov`` that of
    the judged target relative to the bowl (or the gripper, see ``target_by_gripper``). Both
    are what the operator believes of its own precision: the bias's variance and the look's
    averaged noise. Every task judges these; what else a task judges is in ``marks``.

    Attributes:
        gripper_seen: The display shows the gripper (in the cloud or as the ghost).
        closure_known: The display shows whether the gripper is closed.
        target_by_gripper: The target was judged from the gripper (the bowl in hand hidden, or
            a task that aims the gripper itself): the bowl's place in the hand adds its own
            uncertainty.
        lead_m: How far ahead of the frame's own arm the gripper judged is (m): the predictive
            ghost's lead, zero without it. The bowl is seen in the frame, a round trip old: a
            bowl carried by the hand is that much behind where the judged gripper carries it.
        gripper_fixations: The fixations the gripper's judgement against the bowl took: one
            per label read and per drawn thing no other fixation covers
            (:func:`~arteleop.operator.simulated.acuity.fixations`).
        target_fixations: ...and the target's judgement.
        arm_stopped: The display's out-of-reach notice is on
            (:attr:`~arteleop.ar_features.DisplayFrame.reachable`): the gripper shown has stopped
            short of where the hand commands it.
        marks: The marks the task judges besides the target (:attr:`~arteleop.operator.Task.marks`),
            by name, each where it is judged (``mark_m``), its believed covariance relative to
            the judged gripper (``cov``, m^2) and the fixations it took; a mark the display does
            not give is absent (pointing's ``"start"``, the centre of its cross).
    """

    gripper_m: NDArray[np.float64]
    bowl_m: NDArray[np.float64] | None
    target_m: NDArray[np.float64]
    gripper_seen: bool
    closure_known: bool
    gripper_cov: NDArray[np.float64]
    target_cov: NDArray[np.float64]
    target_by_gripper: bool
    lead_m: NDArray[np.float64] = field(default_factory=lambda: np.zeros(3))
    gripper_fixations: int = 1
    target_fixations: int = 1
    marks: Mapping[str, Mark] = field(default_factory=dict)
    arm_stopped: bool = False


def perceive(
    view: DisplayFrame,
    params: PerceptionParams,
    errors: PerceptualErrors,
    depth_factor: float = 1.0,
    depth_scale: float = 1.0,
    aims_gripper: bool = False,
    marks: MarkMemory | None = None,
    judged: Sequence[str] = (),
) -> Perceived:
    """One glance at the display frame ``view``, averaged with this look's earlier glances.

    Every judgement is of a drawn thing's place relative to another, with the precision
    :func:`judgement_sd` gives for what is drawn: the interval between them, their grain and
    the display's stereo. ``depth_factor`` scales the person's depth SD; ``depth_scale`` is how
    the person sees a depth interval in the rendered scene (1: true), a lasting error the person
    does not know of, so it is not in the believed covariances. Where the task ``aims_gripper``
    (pointing), the target is judged against the gripper shown over it, not the bowl. ``judged``
    names the marks the task judges besides it (:func:`judgeable_marks`: pointing's start). A
    mark the display does not draw is judged from ``marks``, the operator's memory of the marks,
    which this glance's judgements update (a fresh memory: none seen yet)."""
    judge = Judge(view, params, errors, depth_factor, depth_scale, marks)
    cues = view.cues
    gripper_seen = view.gripper_in_camera or cues.ghost or cues.predictive_ghost
    bowl = bowl_cov = None
    if view.bowl_m is not None:
        bowl, bowl_cov = judge.seen("bowl", view.bowl_m, view.target_m, judge.cloud_grain)
    grasp = judge_grasp(judge, gripper_seen, bowl, bowl_cov)
    placement = judge_placement(judge, gripper_seen, bowl, bowl_cov, grasp, aims_gripper)
    judged_marks = {}
    for name in judged:
        mark = MARK_JUDGEMENTS[name](judge, gripper_seen, grasp)
        if mark is not None:
            judged_marks[name] = mark
    closure_known = gripper_seen or cues.grip_bar
    return Perceived(
        grasp.gripper_m, bowl, placement.target_m, gripper_seen, closure_known, grasp.cov,
        placement.cov, placement.by_gripper, grasp.lead_m, grasp.fixations,
        placement.fixations, judged_marks, not view.reachable,
    )  # fmt: skip


@dataclass(frozen=True)
class GraspJudgement:
    """The gripper judged, with its believed covariance alone (``gripper_cov``) and relative
    to the bowl (``cov``), m and m^2; the fixations it took; how far ahead of the frame's own
    arm the gripper judged is (``lead_m``, m: the predictive ghost's lead where the judgement
    is of the ghost, none where it is of the frame's arm, as through the beam or the bar)."""

    gripper_m: NDArray[np.float64]
    gripper_cov: NDArray[np.float64]
    cov: NDArray[np.float64]
    fixations: int
    lead_m: NDArray[np.float64] = field(default_factory=lambda: np.zeros(3))


@dataclass(frozen=True)
class PlacementJudgement:
    """The target judged (m), its believed covariance (m^2), whether it was judged from the
    gripper (the bowl in hand hidden), and the fixations it took."""

    target_m: NDArray[np.float64]
    cov: NDArray[np.float64]
    by_gripper: bool
    fixations: int


def judge_grasp(
    judge: Judge,
    gripper_seen: bool,
    bowl: NDArray[np.float64] | None,
    bowl_cov: NDArray[np.float64] | None,
) -> GraspJudgement:
    """The gripper against the bowl's grasp point (``bowl``: the bowl judged this glance, None
    where the display does not show it): through the beam and the distance bar where they are
    drawn, the depth aids' line where the gripper is above the rim; against a remembered bowl;
    or, the gripper not shown, felt from one's own arm."""
    view, params, errors = judge.view, judge.params, judge.errors
    tracked = view.bowl_m
    grasp = view.grasp_point_m()  # what the beam and the distance bar draw
    reference = grasp if grasp is not None else view.target_m
    if gripper_seen and grasp is not None and tracked is not None and bowl is not None:
        # Judged relative to the bowl. The beam draws the gripper-to-grasp interval with the
        # display's grain; the bar's label gives its length: both show nothing while the bowl
        # is not tracked.
        cues = view.cues
        grain = params.display.pixel_rad if cues.beam else judge.cloud_grain
        beam = view.gripper_m - grasp
        read_m: tuple[NDArray[np.float64], ...] = ()
        ahead = np.zeros(3)  # the beam and the bar hang from the frame's arm, as the line does
        if cues.distance_bar and np.linalg.norm(beam) > 1e-6:
            reading = reading_sd_m(DISTANCE_LABEL_STEP_M)
            judged, grasp_cov = judge.seen("gripper", view.gripper_m, grasp, grain, reading, beam)
            seen_m = (view.gripper_m, grasp)
            read_m = (view.distance_label_m(),)
        elif cues.beam:
            judged, grasp_cov = judge.seen("gripper", view.gripper_m, grasp, grain)
            seen_m = (view.gripper_m, grasp)
        else:
            judged, grasp_cov = judge.seen("gripper", judge.shown_gripper, grasp, grain)
            seen_m = (judge.shown_gripper, grasp)
            ahead = judge.lead_m
        if view.depth_aids and view.gripper_m[2] >= grasp[2]:
            # The drop line passes the rim's height where the gripper, lowered, would be: the
            # rim against that point of the line, both level.
            on_line = view.drop_line_at_m(float(grasp[2]))
            aided, aided_info = judge.held_level("grasp on the line", grasp, on_line, grain, ahead)
            relative, grasp_cov = combined(grasp - judged, grasp_cov, aided, aided_info)
            judged = grasp - relative
            seen_m += (on_line,)
        return GraspJudgement(
            bowl + judged - tracked, grasp_cov, grasp_cov,
            judge.fixated(*seen_m, read_m=read_m), ahead,
        )  # fmt: skip
    if gripper_seen:  # against a remembered bowl: seen apart, in other glances
        # The marker is judged against it in the placement: their interval is stretched there.
        gripper, gripper_cov = judge.seen(
            "gripper", judge.shown_gripper, reference, judge.cloud_grain, stretched=False
        )
        return GraspJudgement(gripper, gripper_cov, 2 * gripper_cov, 1, judge.lead_m)
    z = errors.draw("proprioception", 3) * params.proprioception_sd_m
    scale = params.belief_scale(errors.glances("proprioception"))
    felt_cov = np.eye(3) * params.proprioception_sd_m**2 * scale
    grasp_cov = felt_cov if bowl_cov is None else felt_cov + bowl_cov
    return GraspJudgement(view.gripper_m + z, felt_cov, grasp_cov, 1)  # the bowl, the arm felt


def judge_placement(
    judge: Judge,
    gripper_seen: bool,
    bowl: NDArray[np.float64] | None,
    bowl_cov: NDArray[np.float64] | None,
    grasp: GraspJudgement,
    aims_gripper: bool,
) -> PlacementJudgement:
    """The target: against the gripper over it (a task that ``aims_gripper``); as the real
    bowl's coincidence with the target mesh; as where the gripper would hold the mesh (the bowl
    in hand hidden); else the marker in the cloud, against the bowl or the gripper, its centre
    found by bisecting its circle."""
    view, params = judge.view, judge.params
    cues, tracked, shown = view.cues, view.bowl_m, judge.shown_gripper
    # The target as drawn: the mesh where the AR layers put it, or the marker in the cloud.
    mark_point = view.target_m if cues.target_mesh else view.in_cloud(view.target_m)
    drawn = 1.0 if cues.target_mesh else view.target_drawn  # the mesh is drawn over all
    if aims_gripper and gripper_seen:

        def against_gripper() -> Mark:  # the mark against the gripper over it
            grain = params.display.pixel_rad if cues.target_mesh else judge.cloud_grain
            mark, mark_cov = judge.seen("target", mark_point, shown, grain)
            mark, mark_cov, fixations = judge.with_aids(
                "target", mark_point, mark, mark_cov, grain, read_height=False
            )
            centring, centring_cov = judge.centre(mark_point, grain)
            target = grasp.gripper_m + mark - shown + centring
            return Mark(target, mark_cov + centring_cov, fixations)

        aimed = judge.mark("target", drawn, shown, against_gripper)
        return PlacementJudgement(aimed.mark_m, aimed.cov, True, aimed.fixations)
    if cues.target_mesh and bowl is not None and tracked is not None:
        # Coincidence of the real and the virtual bowl: their offset, at the mesh's grain.
        offset_m = float(np.linalg.norm((tracked - view.target_m)[:2]))
        grain = max(judge.cloud_grain, params.display.pixel_rad)
        sd = judge.precision(view.target_m, offset_m, grain)
        offset, cov = judge.planar("coincidence", sd.across_sd_m)
        target = bowl + view.target_m - tracked + offset
        return PlacementJudgement(target, cov, False, judge.fixated(view.target_m, tracked))
    if cues.target_mesh and gripper_seen:
        # The bowl in hand is hidden (the arm is over it): the gripper is put where it would
        # hold the virtual bowl, judged against the mesh beside it, a grasp radius away.
        sd = judge.precision(view.target_m, view.grasp_radius_m, params.display.pixel_rad)
        offset, cov = judge.planar("coincidence", sd.across_sd_m)
        target = grasp.gripper_m + view.target_m - shown + offset
        return PlacementJudgement(target, cov, True, judge.fixated(view.target_m, shown))
    # The marker is drawn in the cloud (or, as a mesh with nothing to coincide with, over it)
    # and centred on by eye: its centre bisects the circle, a radius from its rim. Against the
    # bowl, their interval was stretched in the bowl's judgement.
    against = bowl if bowl is not None else shown

    def in_cloud() -> Mark:
        marker, marker_cov = judge.seen(
            "target", mark_point, against, judge.cloud_grain, stretched=bowl is None
        )
        fixations = judge.fixated(mark_point, against)
        if bowl is None and gripper_seen:
            marker, marker_cov, fixations = judge.with_aids(
                "target", mark_point, marker, marker_cov, judge.cloud_grain, read_height=False
            )
        centring, centring_cov = judge.centre(mark_point, judge.cloud_grain)
        return Mark(marker + centring, marker_cov + centring_cov, fixations)

    marker = judge.mark("target", drawn, against, in_cloud)
    by_gripper = bowl_cov is None
    cov = marker.cov + (grasp.gripper_cov if by_gripper else bowl_cov)
    return PlacementJudgement(marker.mark_m, cov, by_gripper, marker.fixations)

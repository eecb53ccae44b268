"""What the operator sees on the display, and how well: judgements by visible cue.

The operator never reads the simulator's state. At each glance it judges the gripper, the bowl
and the target from what the display frame shows; how precisely depends only on the cues the
frame shows (:class:`PerceptionParams`; each value's source is in docs/operator-model.md):

- the bowl is seen only when the camera shows it (``DisplayFrame.bowl_m``); hidden by the arm,
  it is not seen, and the operator relies on memory (:class:`BowlMemory`);
- the point cloud alone gives good lateral but poor depth judgement along the line of sight;
- the distance bar gives the gripper-to-grasp-point distance, the beam its direction;
- the target mesh turns placement into a coincidence judgement: of the bowl with the mesh, or,
  while the arm hides the bowl in hand, of the gripper with where it would hold the mesh (and
  then the bowl's place in the hand, judged at the grasp, adds its own uncertainty);
- the ghost shows the arm when the camera cannot; without it, an unseen gripper is estimated
  from the operator's own arm (proprioception);
- what the point cloud shows is displaced by the camera's registration error
  (``DisplayFrame.T_cloud_true``), the AR layers are not.

Each judgement's error has two parts (:class:`PerceptualErrors`): a **bias** that lasts, the same
for a person and a judgement in every look and every trial of a study, and **noise** fresh at
each glance, which a longer look averages away. The operator knows how precise a judgement is
(its covariance, :class:`Perceived`), not its own bias.
"""

from __future__ import annotations

import zlib
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from arteleop.ar_features import DisplayFrame
from arteleop.checks import Bounds, check_fields


@dataclass(frozen=True)
class PerceptionParams:
    """Standard deviations (m) of single judgements, and how their errors split.

    Attributes:
        depth_sd_m: Along the line of sight, a point of the point cloud.
        lateral_sd_m: Across the line of sight, a point of the point cloud.
        bar_sd_m: Reading the distance bar.
        beam_sd_m: Across the beam, aligning with it.
        centring_fraction: Centring by eye over the target circle, SD per axis as a share of
            the circle's diameter.
        target_mesh_sd_m: Making the real and the virtual bowl coincide, per axis.
        proprioception_sd_m: Estimating an unseen gripper from one's own arm, per axis.
        bias_share: Share of each judgement's variance that lasts (the person's bias); the rest
            is fresh at every glance. The SDs above are those of one glance.
    """

    depth_sd_m: float = 0.015
    lateral_sd_m: float = 0.004
    bar_sd_m: float = 0.003
    beam_sd_m: float = 0.002
    centring_fraction: float = 0.008 / 0.12
    target_mesh_sd_m: float = 0.003
    proprioception_sd_m: float = 0.03
    bias_share: float = 0.5

    def __post_init__(self) -> None:
        check_fields(self, {"bias_share": Bounds(0, 1)})

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
        """One more glance at ``stream``: the bias plus the mean of this look's fresh noise."""
        bias, fresh = self.draw_parts(stream, size)
        return self._bias_sd * bias + self._fresh_sd * fresh

    def draw_parts(self, stream: str, size: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """One more glance at ``stream``: its bias and the mean of this look's fresh noise,
        each in standard units, unweighted."""
        n, total = self._sums.get(stream, (0, np.zeros(size)))
        n, total = n + 1, total + self._rng.normal(0.0, 1.0, size)
        self._sums[stream] = (n, total)
        return self.bias(stream, size), total / n

    def bias(self, stream: str, size: int) -> NDArray[np.float64]:
        """The person's lasting bias of ``stream`` (standard units)."""
        bias = self._bias.get(stream)
        if bias is None:
            stream_rng = np.random.default_rng([self._seed, zlib.crc32(stream.encode())])
            bias = self._bias[stream] = stream_rng.normal(0.0, 1.0, size)
        return bias

    @property
    def shares(self) -> tuple[float, float]:
        """(bias SD, fresh SD) in standard units: the split of a glance's error."""
        return self._bias_sd, self._fresh_sd

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
) -> Perceived:
    """One glance at the display frame ``view``: judgements whose errors depend on the visible
    cues, averaged with this look's earlier glances. ``depth_factor`` scales the point cloud's
    depth SD (the person's depth judgement)."""
    cues = view.cues
    depth_sd = params.depth_sd_m * depth_factor
    lateral_sd = params.lateral_sd_m
    gripper_seen = view.gripper_in_camera or cues.ghost or cues.predictive_ghost
    shown_gripper = shown_gripper_m(view)

    def seen(
        stream: str,
        point: NDArray[np.float64],
        along_sd: float,
        across_sd: float,
        axis: NDArray[np.float64] | None = None,
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """``point`` judged with ``along_sd`` along ``axis`` and ``across_sd`` across it: the
        judgement and its believed covariance.

        Without an axis it is a point of the cloud, judged along the line of sight. Its
        lasting error is then the view's, shared by every point of the cloud (a viewer
        compresses a rendered scene's depth as a whole, and misplaces what a view shows
        together), so it cancels between two points compared with each other: the covariance
        returned is the one of such a comparison, fresh noise only (:func:`absolute` adds the
        view's part back)."""
        d = point - view.viewpoint_m if axis is None else axis
        d = d / np.linalg.norm(d)
        bias, fresh = errors.draw_parts(stream, 4)
        bias_sd, fresh_sd = errors.shares
        scale = params.belief_scale(errors.glances(stream))
        if axis is None:
            bias = errors.bias("scene", 4)
            scale = (1.0 - params.bias_share) / errors.glances(stream)
        z = bias_sd * bias + fresh_sd * fresh
        across = z[1:] * across_sd
        across -= d * (across @ d)
        along = np.outer(d, d)
        cov = scale * (along_sd**2 * along + across_sd**2 * (np.eye(3) - along))
        return point + d * (z[0] * along_sd) + across, cov

    def absolute(point: NDArray[np.float64], cov: NDArray[np.float64]) -> NDArray[np.float64]:
        """A cloud point's covariance judged on its own: the view's lasting error added."""
        d = (point - view.viewpoint_m) / np.linalg.norm(point - view.viewpoint_m)
        along = np.outer(d, d)
        view_part = depth_sd**2 * along + lateral_sd**2 * (np.eye(3) - along)
        return cov + params.bias_share * view_part

    def planar(stream: str, sd: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """An error in the table's plane with ``sd`` per axis, and its covariance."""
        z = errors.draw(stream, 2) * sd
        cov = np.diag([sd**2, sd**2, 0.0]) * params.belief_scale(errors.glances(stream))
        return np.append(z, 0.0), cov

    tracked = view.bowl_m
    grasp = view.grasp_point_m()  # what the beam and the distance bar draw
    bowl = bowl_cov = None
    if tracked is not None:
        bowl, bowl_cov = seen("bowl", tracked, depth_sd, lateral_sd)
    if gripper_seen and grasp is not None and tracked is not None and bowl is not None:
        # Judged relative to the bowl. The bar gives the gripper's distance to the grasp point
        # and the beam its direction: both show nothing while the bowl is not tracked.
        if cues.distance_bar or cues.beam:
            along_sd = params.bar_sd_m if cues.distance_bar else depth_sd
            across_sd = params.beam_sd_m if cues.beam else lateral_sd
            beam = view.gripper_m - grasp
            axis = beam if np.linalg.norm(beam) > 1e-6 else None
            judged, grasp_cov = seen("gripper", view.gripper_m, along_sd, across_sd, axis)
        else:
            judged, grasp_cov = seen("gripper", shown_gripper, depth_sd, lateral_sd)
        gripper = bowl + judged - tracked
        gripper_cov = grasp_cov
    elif gripper_seen:  # against a remembered bowl: seen apart, in other glances
        gripper, gripper_cov = seen("gripper", shown_gripper, depth_sd, lateral_sd)
        grasp_cov = 2 * absolute(shown_gripper, gripper_cov)
    else:
        z = errors.draw("proprioception", 3) * params.proprioception_sd_m
        gripper = view.gripper_m + z
        scale = params.belief_scale(errors.glances("proprioception"))
        grasp_cov = np.eye(3) * params.proprioception_sd_m**2 * scale
        gripper_cov = grasp_cov
        if bowl_cov is not None and tracked is not None:
            grasp_cov = grasp_cov + absolute(tracked, bowl_cov)
    placed_by_gripper = False
    if cues.target_mesh and bowl is not None:
        # Coincidence of the real and the virtual bowl: judged relative to the bowl.
        offset, placement_cov = planar("coincidence", params.target_mesh_sd_m)
        target = bowl + view.target_m - tracked + offset
    elif cues.target_mesh and gripper_seen:
        # The bowl in hand is hidden (the arm is over it): the gripper is put where it would
        # hold the virtual bowl, judged against the mesh beside it.
        offset, placement_cov = planar("coincidence", params.target_mesh_sd_m)
        target = gripper + view.target_m - shown_gripper + offset
        placed_by_gripper = True
    else:
        # The marker is a point of the cloud like the bowl (or the gripper over it), centred on
        # by eye: compared within the cloud, the scene's depth error cancels. A mesh with
        # nothing to coincide with is a point drawn over the cloud: judged on its own.
        point = view.target_m if cues.target_mesh else view.in_cloud(view.target_m)
        marker, marker_cov = seen("target", point, depth_sd, lateral_sd)
        if cues.target_mesh:
            marker_cov = absolute(point, marker_cov)
        centring_sd = params.centring_fraction * 2 * view.target_radius_m
        centring, centring_cov = planar("centring", centring_sd)
        target = marker + centring
        placement_cov = marker_cov + centring_cov
        if bowl_cov is not None:
            placement_cov = placement_cov + bowl_cov
        else:
            placement_cov = placement_cov + gripper_cov
            placed_by_gripper = True
    closure_known = gripper_seen or cues.grip_bar
    predicted = view.shown_predicted
    lead = np.zeros(3) if predicted is None else predicted.gripper_m - view.gripper_m
    return Perceived(
        gripper, bowl, target, gripper_seen, closure_known, grasp_cov, placement_cov,
        placed_by_gripper, lead,
    )  # fmt: skip


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

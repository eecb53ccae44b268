"""What the operator sees on the display, and how well: perception errors by visible cue.

The operator never reads the simulator's state. Each time they look, they estimate the gripper,
the bowl and the target from what the display shows; the error of each estimate depends only on
the cues visible (assumptions, each with its reasoning, in :class:`PerceptionParams`):

- the bowl is seen only when the camera shows it, the same condition under which the tracker
  finds it (``DisplayFrame.bowl_m``); hidden by the arm, it is not seen, and the operator relies
  on memory (:class:`~arteleop.operator.synthetic.SyntheticOperator`);
- the point cloud alone gives good lateral but poor depth judgement along the line of sight;
- the distance bar gives the gripper-to-grasp-point distance, the beam its direction;
- the target mesh turns placement into a coincidence judgement: of the bowl with the mesh, or,
  while the arm hides the bowl in hand, of the gripper with where it would hold the mesh;
- the ghost shows the arm when the camera cannot (out of view, or too close for the sensor);
  without it, an unseen gripper is estimated from the operator's own arm (proprioception);
- what the point cloud shows (the real gripper, the bowl, the target marker) is displaced by the
  camera's registration error (``DisplayFrame.T_cloud_true``), all alike, so judged against each
  other they agree; the AR layers (the ghost, the beam and the bar from the encoders' gripper,
  the target mesh) are not, so a misregistration misleads exactly the judgements they serve.

Errors persist from look to look (:class:`PerceptualNoise`): a person who misjudges the depth of
a point in a scene misjudges it the same way a second later, so corrective movements converge
on what the operator believes, not on the truth, and the belief's bias stays in the result.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from arteleop.ar_features import DisplayFrame
from arteleop.errors import ConfigurationError


@dataclass(frozen=True)
class PerceptionParams:
    """Standard deviations of the operator's estimates (m), and how long their errors persist.

    Attributes:
        depth_sd_m: Along the line of sight, from a point cloud seen in an HMD. Depth from
            disparity and motion parallax in a sparse, noisy cloud is judged several times worse
            than lateral position; 15 mm at about 1.3 m viewing distance.
        lateral_sd_m: Across the line of sight: a few pixels of the 640x480 view at 1.3 m.
        bar_sd_m: Residual distance error when reading the distance bar (its resolution).
        beam_sd_m: Residual lateral error when aligning with the beam.
        target_marker_sd_m: Centring the bowl over the target circle by eye, per axis.
        target_mesh_sd_m: Making the real and the virtual bowl coincide, per axis.
        proprioception_sd_m: Estimating an unseen gripper from one's own arm, per axis.
        persistence_s: Correlation time (s) of each estimate's error: two looks ``dt`` apart
            err with correlation ``exp(-dt / persistence_s)``, each with the SD above. Distance
            judgements in a rendered scene are biased systematically for a given viewer and view
            (Renner et al., ACM Computing Surveys 2013), and what was seen in the last 10-15 s
            pulls the next judgement (serial dependence: Fischer & Whitney, Nature Neuroscience
            2014): 10 s. 0 makes every look independent.
    """

    depth_sd_m: float = 0.015
    lateral_sd_m: float = 0.004
    bar_sd_m: float = 0.003
    beam_sd_m: float = 0.002
    target_marker_sd_m: float = 0.008
    target_mesh_sd_m: float = 0.003
    proprioception_sd_m: float = 0.03
    persistence_s: float = 10.0

    def __post_init__(self) -> None:
        if self.persistence_s < 0:
            raise ConfigurationError(
                f"PerceptionParams.persistence_s is {self.persistence_s}: it must be >= 0 s."
            )


class PerceptualNoise:
    """The operator's estimation errors, in standard units, one stream per estimated quantity.

    Each stream is a first-order autoregressive (Ornstein-Uhlenbeck) process sampled at the
    looks: its marginal distribution is standard normal, and two draws ``dt`` seconds apart have
    correlation ``exp(-dt / persistence_s)``. Scaling by a standard deviation gives the error.
    """

    def __init__(self, rng: np.random.Generator, persistence_s: float) -> None:
        self._rng = rng
        self._persistence_s = persistence_s
        self._streams: dict[str, tuple[float, NDArray[np.float64]]] = {}

    def draw(self, stream: str, time_s: float, size: int) -> NDArray[np.float64]:
        """``size`` standard normal values of ``stream`` at ``time_s`` (s)."""
        fresh = self._rng.normal(0.0, 1.0, size)
        last = self._streams.get(stream)
        if last is not None and self._persistence_s > 0:
            rho = np.exp(-max(time_s - last[0], 0.0) / self._persistence_s)
            fresh = rho * last[1] + np.sqrt(1.0 - rho**2) * fresh
        self._streams[stream] = (time_s, fresh)
        return fresh


@dataclass(frozen=True)
class Perceived:
    """The operator's estimates at one look, base frame (m); ``bowl_m`` is None when the
    display does not show the bowl.

    ``grasp_sd_m`` and ``placement_sd_m`` are how precisely the look judges the gripper against
    the bowl and the bowl against the target: the RMS length (m) of those judgements' errors,
    from the cues the look used. They are what the operator can tell apart.
    """

    gripper_m: NDArray[np.float64]
    bowl_m: NDArray[np.float64] | None
    target_m: NDArray[np.float64]
    gripper_seen: bool
    closure_known: bool
    grasp_sd_m: float
    placement_sd_m: float


def perceive(
    view: DisplayFrame, params: PerceptionParams, noise: PerceptualNoise, noise_scale: float = 1.0
) -> Perceived:
    """One look at the display frame ``view``: estimates with errors that depend on the visible
    cues, drawn from ``noise`` at the frame's time."""
    cues = view.cues
    k = noise_scale
    gripper_seen = view.gripper_in_camera or cues.ghost
    # The ghost draws the gripper where the encoders put it; without it, the operator sees the
    # real gripper in the cloud.
    shown_gripper = view.gripper_m if cues.ghost else view.in_cloud(view.gripper_m)

    def normal(stream: str, sd: float, size: int) -> NDArray[np.float64]:
        return noise.draw(stream, view.time_s, size) * (sd * k)

    def seen(
        stream: str,
        point: NDArray[np.float64],
        along_sd: float,
        across_sd: float,
        axis: NDArray[np.float64] | None = None,
    ) -> NDArray[np.float64]:
        """``point`` judged with ``along_sd`` along ``axis`` (default: the line of sight) and
        ``across_sd`` across it."""
        d = point - view.viewpoint_m if axis is None else axis
        d = d / np.linalg.norm(d)
        z = noise.draw(stream, view.time_s, 4)
        across = z[1:] * (across_sd * k)
        across -= d * (across @ d)
        return point + d * (z[0] * along_sd * k) + across

    tracked = view.bowl_m
    grasp = view.grasp_point_m()  # what the beam and the distance bar draw
    cloud_sd = _rms(params.depth_sd_m, params.lateral_sd_m) * k  # a point of the cloud
    bowl = (
        None if tracked is None else seen("bowl", tracked, params.depth_sd_m, params.lateral_sd_m)
    )
    if gripper_seen and grasp is not None and tracked is not None and bowl is not None:
        # Judged relative to the bowl. The bar gives the gripper's distance to the grasp point
        # and the beam its direction: both show nothing while the bowl is not tracked.
        if cues.distance_bar or cues.beam:
            along_sd = params.bar_sd_m if cues.distance_bar else params.depth_sd_m
            across_sd = params.beam_sd_m if cues.beam else params.lateral_sd_m
            beam = view.gripper_m - grasp
            axis = beam if np.linalg.norm(beam) > 1e-6 else None
            judged = seen("gripper", view.gripper_m, along_sd, across_sd, axis)
            grasp_sd = _rms(along_sd, across_sd) * k
        else:
            judged = seen("gripper", shown_gripper, params.depth_sd_m, params.lateral_sd_m)
            grasp_sd = cloud_sd
        gripper = bowl + judged - tracked
    elif gripper_seen:  # against a remembered bowl
        gripper = seen("gripper", shown_gripper, params.depth_sd_m, params.lateral_sd_m)
        grasp_sd = np.hypot(cloud_sd, cloud_sd)
    else:
        gripper = view.gripper_m + normal("proprioception", params.proprioception_sd_m, 3)
        grasp_sd = np.hypot(np.sqrt(3) * params.proprioception_sd_m * k, cloud_sd)
    if cues.target_mesh and tracked is not None and bowl is not None:
        # Coincidence of the real and the virtual bowl: judged relative to the bowl.
        target = (
            bowl
            + view.target_m
            - tracked
            + np.append(normal("coincidence", params.target_mesh_sd_m, 2), 0.0)
        )
        placement_sd = np.sqrt(2) * params.target_mesh_sd_m * k
    elif cues.target_mesh and gripper_seen:
        # The bowl in hand is hidden (the arm is over it): the gripper is put where it would
        # hold the virtual bowl, judged against the mesh beside it; the bowl's place in the
        # hand is what the operator remembers of the grasp.
        target = (
            gripper
            + view.target_m
            - shown_gripper
            + np.append(normal("coincidence", params.target_mesh_sd_m, 2), 0.0)
        )
        placement_sd = np.sqrt(2) * params.target_mesh_sd_m * k
    elif cues.target_mesh:  # nothing to make it coincide with: a point like any other
        target = seen("target", view.target_m, params.depth_sd_m, params.lateral_sd_m)
        placement_sd = np.hypot(cloud_sd, cloud_sd)
    else:
        # The marker is a point of the cloud like any other, then centred on by eye.
        marker = seen(
            "target", view.in_cloud(view.target_m), params.depth_sd_m, params.lateral_sd_m
        )
        target = marker + np.append(normal("centring", params.target_marker_sd_m, 2), 0.0)
        placement_sd = np.sqrt(2 * cloud_sd**2 + 2 * (params.target_marker_sd_m * k) ** 2)
    closure_known = cues.grip_bar or view.gripper_in_camera or cues.ghost
    return Perceived(
        gripper, bowl, target, gripper_seen, closure_known, float(grasp_sd), float(placement_sd)
    )


def _rms(along_sd: float, across_sd: float) -> float:
    """RMS length of a 3-D error with ``along_sd`` on one axis and ``across_sd`` on two."""
    return float(np.sqrt(along_sd**2 + 2 * across_sd**2))


class BowlMemory:
    """Where the operator believes the bowl is: where a look last showed it, and while it is
    held, where it sits relative to the gripper (it moves with the hand)."""

    def __init__(self) -> None:
        self._last_seen_m: NDArray[np.float64] | None = None
        self._in_hand_m: NDArray[np.float64] | None = None

    def bowl_m(self, seen: Perceived) -> NDArray[np.float64] | None:
        """The bowl after a look: as seen when shown, else as remembered; None before it was
        ever seen."""
        if seen.bowl_m is not None:
            self._last_seen_m = seen.bowl_m
            return seen.bowl_m
        if self._in_hand_m is not None:
            return seen.gripper_m + self._in_hand_m
        return self._last_seen_m

    def grasp(self, seen: Perceived, bowl_m: NDArray[np.float64] | None) -> None:
        """The operator has closed the gripper on the bowl believed at ``bowl_m``."""
        self._in_hand_m = None if bowl_m is None else bowl_m - seen.gripper_m

    def release(self) -> None:
        self._in_hand_m = None

    def left_behind(self, seen: Perceived, drop_m: float = 0.07) -> bool:
        """A look shows the bowl held a moment ago more than ``drop_m`` below where the hand
        should carry it: the grasp missed and the bowl stayed on the table. (Judged in height:
        a held bowl tilts and the estimates err by centimetres, but a lift is 15 cm.)"""
        if seen.bowl_m is None or self._in_hand_m is None:
            return False
        expected = seen.gripper_m + self._in_hand_m
        return bool(expected[2] - seen.bowl_m[2] > drop_m)

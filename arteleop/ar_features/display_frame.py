"""What the operator's display shows at one instant: one plain-data frame.

The view draws it and the synthetic operator perceives it, so a person and the model of one see
the same thing. This module imports neither viser nor the simulator.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np
from numpy.typing import NDArray

from arteleop.ar_features.clearance import Box, discs_in_plane, pushed_out_m
from arteleop.ar_features.modalities import ArCues
from arteleop.arrays import frozen_array
from arteleop.errors import DisplayFrameError

DISTANCE_LABEL_STEP_M = 0.001
"""The distance bar's label shows :meth:`DisplayFrame.grasp_distance_m` to this step (m): what a
reader of the label can know of it."""
HEIGHT_LABEL_STEP_M = 0.001
"""The depth aids' label shows :meth:`DisplayFrame.height_m` to this step (m)."""
FOOT_LIFT_M = 0.01
"""The depth aids' ring and the drop line's foot are drawn this far off the table towards the
head camera, along its line of sight (m), where the camera sees them just where the line meets the
table (lifted straight up, the ring showed a few millimetres beyond): in front of the table's
cloud points, drawn facing the viewer, which hid parts of a ring on the table, and at 5 mm still
some of its edge (a screenshot of the view)."""
FOOT_RADIUS_M = 0.015
"""The ring on the table under the gripper (m): about 9 px at the head camera's 1.3 m."""
HEIGHT_LABEL_GAP_M = 0.03
"""The height's label sits this far beside the ring, in the camera's image plane (m)."""
DISTANCE_BAR_OFFSET_M = (-0.16, -0.03)
"""Where the distance bar's left end is drawn relative to the gripper, in the camera's image
plane (m; x right, y down), so it stays beside the gripper on screen; its label is left of it."""
GRIP_BAR_OFFSET_M = (-0.16, 0.0)
"""Where the grip bar's left end is drawn relative to the gripper, likewise: 3 cm below the
distance bar's."""
BAR_LABEL_GAP_M = 0.01
"""A bar's label ends this far left of the bar (m, in the image plane)."""
LABEL_SIZE_M = (0.10, 0.03)
"""A label's width and height in the image plane at the head camera's 1.3 m (m): "102 mm"
and "grip 0 %" were 38-40 px wide, 12 px tall, beside a 10 cm bar drawn 45 px long, in an
800x500 screenshot of the view; "height 150 mm" is about as wide."""
LABEL_CLEARANCE_M = 0.02
"""The labels (the height's, the bars') keep this far clear of the target and the bowl in the
image plane (m): drawn over them, they hid the very things a person places by."""


@dataclass(frozen=True)
class PredictedArm:
    """Where the commands the operator has already sent will put the arm, at the operator's
    present: what the predictive ghost draws, ahead of the delayed frame it is drawn over.

    Attributes:
        time_s: The operator's present, when the newest command was sent (simulated time, s).
        arm_q_rad: (7,) the right arm's joint targets those commands give (rad).
        T_base_gripper: (4, 4) the gripper's tool frame at those joints (base frame, m).
        gripper_closure: The gripper's commanded closure, 0 (open) .. 1 (closed).
    """

    time_s: float
    arm_q_rad: NDArray[np.float64]
    T_base_gripper: NDArray[np.float64]
    gripper_closure: float

    def __post_init__(self) -> None:
        for name, shape in (("arm_q_rad", (7,)), ("T_base_gripper", (4, 4))):
            value = frozen_array(getattr(self, name))
            if value.shape != shape:
                raise DisplayFrameError(
                    f"PredictedArm.{name} must have shape {shape}, got {value.shape}"
                )
            object.__setattr__(self, name, value)

    @property
    def gripper_m(self) -> NDArray[np.float64]:
        """The predicted gripper's tool-frame position (m)."""
        return self.T_base_gripper[:3, 3]


@dataclass(frozen=True)
class DisplayFrame:
    """The display's content at one instant, in Baxter's base frame (m).

    Attributes:
        time_s: When the remote system captured this content (simulated time, s).
        T_base_camera: (4, 4) pose of the head camera's optical frame: the operator's eye.
        arm_q_rad: (7,) right-arm joint positions from the robot's encoders (rad).
        T_base_gripper: (4, 4) pose of the gripper's tool frame at those joint positions.
        gripper_closure: The gripper's measured closure, 0 (open) .. 1 (closed).
        gripper_in_camera: The head camera captures the gripper (in the image and depth range).
        bowl_m: (3,) the bowl's frame (centre of its bottom face) as the head camera tracks it,
            or None when the tracker has no estimate (the bowl is out of view or hidden, e.g.
            by the arm): the display never falls back to the simulator's truth.
        grasp_radius_m: Radius of the ring of grasp points (the middle of the wall), about the
            bowl's axis (m).
        grasp_height_m: Height of that ring above the bowl's frame (m).
        target_m: (3,) the target point on the table.
        start_m: (3,) the start point on the table, the centre of its cross (None: not given).
        cues: The AR layers shown.
        engaged: The status indicator: the robot follows the operator's hand.
        reachable: The out-of-reach notice is off: False while the gripper is short of where
            the operator's hand commands it in the table's plane and the IK has found that
            target out of reach (``teleop.loop.OUT_OF_REACH_M``). A status, as ``engaged`` is,
            in every condition. The served page shows people the same notice from the trial's
            progress at the camera's tick, without the return link's delay this frame has.
        cloud_points_m: (N, 3) float32 point cloud of the camera frame, or None when this
            instant was not rendered (batch runs render only to track the bowl).
        cloud_colors: (N, 3) uint8 colours of the cloud's points, or None.
        cloud_spacing_rad: The angle between neighbouring points of the cloud as the camera saw
            them (rad): a pixel's angle times the decimation; a point's footprint is this times
            its distance.
        target_radius_m: Radius of the target circle drawn on the table (m).
        T_cloud_true: (4, 4) where the point cloud shows a point of the real scene: the
            camera's registration error, in the base frame (None: a perfect registration).
            A real system cannot know it; the simulation gives it so that the synthetic
            operator sees the real gripper and the markers where the cloud shows them,
            off the ghost and the target mesh, which stay where the robot and the task put
            them. The view draws the cloud itself and does not use it.
        predicted: Where the commands already sent will put the arm, at the operator's present
            (newer than ``time_s`` by the round trip); None where nothing predicts it (the
            predictive ghost then draws the arm of this frame).
        depth_aids: The depth aids are drawn: a line from the gripper straight down to the
            table, a ring where it meets it, and the gripper's height above the table. They are
            no AR layer: a study shows them in every condition or in none (what a flat screen
            lacks against the original's head-mounted display: stereo and head motion).
    """

    time_s: float
    T_base_camera: NDArray[np.float64]
    arm_q_rad: NDArray[np.float64]
    T_base_gripper: NDArray[np.float64]
    gripper_closure: float
    gripper_in_camera: bool
    bowl_m: NDArray[np.float64] | None
    grasp_radius_m: float
    grasp_height_m: float
    target_m: NDArray[np.float64]
    cues: ArCues
    engaged: bool
    cloud_points_m: NDArray[np.float32] | None = None
    cloud_colors: NDArray[np.uint8] | None = None
    T_cloud_true: NDArray[np.float64] | None = None
    target_radius_m: float = 0.06
    cloud_spacing_rad: float | None = None
    predicted: PredictedArm | None = None
    start_m: NDArray[np.float64] | None = None
    depth_aids: bool = False
    target_drawn: float = 1.0
    start_drawn: float = 1.0
    reachable: bool = True

    def __post_init__(self) -> None:
        shapes = {
            "T_base_camera": (4, 4),
            "arm_q_rad": (7,),
            "T_base_gripper": (4, 4),
            "bowl_m": (3,),
            "target_m": (3,),
            "T_cloud_true": (4, 4),
            "start_m": (3,),
        }
        for name, shape in shapes.items():
            if name in ("bowl_m", "T_cloud_true", "start_m") and getattr(self, name) is None:
                continue
            value = frozen_array(getattr(self, name))
            if value.shape != shape:
                raise DisplayFrameError(
                    f"DisplayFrame.{name} must have shape {shape}, got {value.shape}"
                )
            object.__setattr__(self, name, value)
        if (
            not (self.cloud_points_m is None)
            == (self.cloud_colors is None)
            == (self.cloud_spacing_rad is None)
        ):
            raise DisplayFrameError(
                "DisplayFrame needs cloud_points_m, cloud_colors and cloud_spacing_rad together"
            )
        for name in ("target_drawn", "start_drawn"):
            if not 0.0 <= getattr(self, name) <= 1.0:
                raise DisplayFrameError(
                    f"DisplayFrame.{name}={getattr(self, name)}: expected a share from 0 to 1"
                )
        spacing = self.cloud_spacing_rad
        if spacing is not None and not (np.isfinite(spacing) and spacing > 0):
            raise DisplayFrameError(
                f"DisplayFrame.cloud_spacing_rad={spacing}: expected a positive angle (rad)"
            )
        if self.cloud_points_m is not None:
            # Views, not copies: a 640x480 cloud is rebuilt every frame and never changed.
            points = np.asarray(self.cloud_points_m, dtype=np.float32).view()
            colors = np.asarray(self.cloud_colors, dtype=np.uint8).view()
            if points.ndim != 2 or points.shape[1] != 3 or colors.shape != points.shape:
                raise DisplayFrameError(
                    "DisplayFrame's cloud needs points (N, 3) and colours (N, 3); got "
                    f"{points.shape} and {colors.shape}"
                )
            points.setflags(write=False)
            colors.setflags(write=False)
            object.__setattr__(self, "cloud_points_m", points)
            object.__setattr__(self, "cloud_colors", colors)

    @property
    def viewpoint_m(self) -> NDArray[np.float64]:
        """The camera's optical centre: where the operator looks from (m)."""
        return self.T_base_camera[:3, 3]

    @property
    def gripper_m(self) -> NDArray[np.float64]:
        """The gripper's tool-frame position (m)."""
        return self.T_base_gripper[:3, 3]

    def beside_gripper_m(self, offset_m: tuple[float, float]) -> NDArray[np.float64]:
        """The point ``offset_m`` from the gripper in the camera's image plane (m; x right, y
        down): where a layer drawn beside the gripper on screen goes (base frame, m)."""
        R = self.T_base_camera[:3, :3]
        return self.gripper_m + R @ np.array([offset_m[0], offset_m[1], 0.0])

    def height_m(self) -> float:
        """The gripper's height above the table top, where the target marker lies (m)."""
        return float(self.gripper_m[2] - self.target_m[2])

    def height_shown_m(self) -> float:
        """The height the depth aids' label shows: :meth:`height_m` to
        :data:`HEIGHT_LABEL_STEP_M` (m)."""
        return round(self.height_m() / HEIGHT_LABEL_STEP_M) * HEIGHT_LABEL_STEP_M

    def drop_foot_m(self) -> NDArray[np.float64]:
        """Where the line from the gripper straight down meets the table (base frame, m); the
        ring is drawn :data:`FOOT_LIFT_M` from it towards the camera."""
        return np.append(self.gripper_m[:2], self.target_m[2])

    def ring_m(self) -> NDArray[np.float64]:
        """The centre of the depth aids' ring (base frame, m), where the drawn line ends:
        :data:`FOOT_LIFT_M` from :meth:`drop_foot_m` towards the camera, on its line of sight."""
        foot = self.drop_foot_m()
        toward = self.viewpoint_m - foot
        return foot + FOOT_LIFT_M * toward / np.linalg.norm(toward)

    def drop_line_at_m(self, height_m: float) -> NDArray[np.float64]:
        """Where the drawn drop line, from the gripper to :meth:`ring_m`, passes the height
        ``height_m`` (base frame z, m; between the two ends)."""
        top, foot = self.gripper_m, self.ring_m()
        share = (top[2] - height_m) / (top[2] - foot[2]) if top[2] != foot[2] else 0.0
        return top + float(np.clip(share, 0.0, 1.0)) * (foot - top)

    def height_label_m(self) -> NDArray[np.float64]:
        """Where the depth aids' label is drawn (base frame, m): beside the ring in the
        camera's image plane, on the side towards the image's middle (its end nearest the ring
        there, :meth:`height_label_leftward`), so that near the image's edge it stays in the
        view (right of a ring at rest, at the right edge, it went under the side panel); and
        beyond the target and the bowl where they lie level with it, by
        :data:`LABEL_CLEARANCE_M` (over the target, it sat on the circle being placed on)."""
        ring = self.ring_m()
        side = -1.0 if self._leftward_of(ring) else 1.0
        near = FOOT_RADIUS_M + HEIGHT_LABEL_GAP_M
        w, h = LABEL_SIZE_M
        box = (near, near + w, -h / 2, h / 2) if side > 0 else (-near - w, -near, -h / 2, h / 2)
        out = near + self._kept_clear_by_m(ring, box)
        return ring + side * self.T_base_camera[:3, 0] * out

    @property
    def height_label_leftward(self) -> bool:
        """The height's label is drawn left of the ring: the ring is right of the image's
        middle."""
        return self._leftward_of(self.ring_m())

    def _leftward_of(self, ring_m: NDArray[np.float64]) -> bool:
        """A ring at ``ring_m`` lies right of the image's middle (its label goes left)."""
        return bool((ring_m - self.viewpoint_m) @ self.T_base_camera[:3, 0] > 0.0)

    def distance_label_m(self) -> NDArray[np.float64]:
        """Where the distance bar's label is drawn (base frame, m), its right end."""
        return self.bar_label_m(DISTANCE_BAR_OFFSET_M)

    def bar_label_m(self, offset_m: tuple[float, float]) -> NDArray[np.float64]:
        """Where the label of the bar whose left end is ``offset_m`` from the gripper is drawn
        (base frame, m; the label's right end): :data:`BAR_LABEL_GAP_M` left of the bar, and
        further left, beyond the target and the bowl where they lie level with it, by
        :data:`LABEL_CLEARANCE_M` (near the end of a carry it sat on the target being placed
        on). Always left: right of the gripper at rest, at the image's right edge, the bars
        went under the side panel."""
        x, y = offset_m
        right = x - BAR_LABEL_GAP_M
        w, h = LABEL_SIZE_M
        out = self._kept_clear_by_m(self.gripper_m, (right - w, right, y - h / 2, y + h / 2))
        return self.beside_gripper_m((right - out, y))

    def _kept_clear_by_m(self, anchor_m: NDArray[np.float64], box: Box) -> float:
        """How far a label's ``box``, in the image plane through ``anchor_m`` (m, relative to
        it), moves outwards to keep :data:`LABEL_CLEARANCE_M` from the target circle, the
        target mesh over it and the tracked bowl (its ring of grasp points), as drawn (m)."""
        up = np.array([0.0, 0.0, self.grasp_height_m])
        things = [(self.target_m, self.target_radius_m)]
        if self.cues.target_mesh:
            things.append((self.target_m + up, self.grasp_radius_m))
        if self.bowl_m is not None:
            things.append((self.bowl_m + up, self.grasp_radius_m))
        discs = discs_in_plane(self.T_base_camera, anchor_m, things)
        return pushed_out_m(box, discs, LABEL_CLEARANCE_M)

    def in_cloud(self, point_m: NDArray[np.float64]) -> NDArray[np.float64]:
        """Where the point cloud shows the real scene's ``point_m`` (base frame, m)."""
        if self.T_cloud_true is None:
            return point_m
        return self.T_cloud_true[:3, :3] @ point_m + self.T_cloud_true[:3, 3]

    @property
    def shown_predicted(self) -> PredictedArm | None:
        """The predicted arm where the predictive ghost is on and has a prediction to draw."""
        return self.predicted if self.cues.predictive_ghost else None

    @property
    def has_cloud(self) -> bool:
        return self.cloud_points_m is not None

    @property
    def bowl_found(self) -> bool:
        """The tracker has an estimate of the bowl in this frame."""
        return self.bowl_m is not None

    def grasp_point_m(self) -> NDArray[np.float64] | None:
        """The grasp point closest to the gripper (m): the point of the tracked bowl's grasp
        ring in the gripper's direction from the bowl's axis (+y when the gripper is on the
        axis); None when the bowl is not tracked.

        The beam and the distance bar draw it, and the synthetic operator perceives it.
        """
        if self.bowl_m is None:
            return None
        d = self.gripper_m[:2] - self.bowl_m[:2]
        n = float(np.hypot(d[0], d[1]))
        d = d / n if n > 1e-9 else np.array([0.0, 1.0])
        ring = np.array([d[0] * self.grasp_radius_m, d[1] * self.grasp_radius_m, 0.0])
        return self.bowl_m + ring + [0.0, 0.0, self.grasp_height_m]

    def grasp_distance_m(self) -> float | None:
        """Distance from the gripper to :meth:`grasp_point_m` (m), the distance bar's value;
        None when the bowl is not tracked."""
        grasp = self.grasp_point_m()
        return None if grasp is None else float(np.linalg.norm(grasp - self.gripper_m))


class Display(Protocol):
    """Where display frames go, e.g. :class:`arteleop.ar_features.OperatorView`."""

    def show(self, frame: DisplayFrame) -> None: ...

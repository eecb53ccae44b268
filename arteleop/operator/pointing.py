"""A Fitts pointing task for the synthetic operator, through the whole teleoperation chain: the
calibration task of docs/operator-model.md.

The operator brings the gripper over a start point, then over a target circle drawn on the table
(its diameter the target's width), and selects it by closing the gripper. It is the
pick-and-place operator with another script: the same looks, criterion test, planner, homing and
lag; the pointing movement is judged as the placement without the target mesh is (the circle
as a point of the cloud, centred on by eye, against one more point of the cloud: the bowl's or,
where the bowl is not in view, the gripper's), its criterion half the target's width (the
operator aims to end inside the circle).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from arteleop.ar_features import DisplayFrame
from arteleop.operator.arm_model import ArmModel
from arteleop.operator.perception import Perceived
from arteleop.operator.posture import CalibrationPosture
from arteleop.operator.sources import WearableSample, WornSource
from arteleop.operator.synthetic import (
    OperatorParams,
    Phase,
    SyntheticOperator,
    TaskGeometry,
)
from arteleop.operator.traits import OperatorTraits


@dataclass(frozen=True)
class PointingTask:
    """One pointing trial (base frame, m).

    Attributes:
        start_m: Where the gripper waits before the movement (over the start point).
        target_m: The target's centre on the table.
        width_m: The target's width: the circle's diameter.
        height_m: How high over the table the gripper points.
    """

    start_m: NDArray[np.float64]
    target_m: NDArray[np.float64]
    width_m: float
    height_m: float = 0.05


class PointingOperator(SyntheticOperator):
    """Points from ``task.start_m`` at ``task.target_m`` and selects by closing the gripper.

    After the selection, :attr:`selected_s` is when it decided, :attr:`movement_start_s` when
    the pointing movement began (s).
    """

    def __init__(
        self,
        task: PointingTask,
        rest_gripper_m: NDArray[np.float64],
        hand_for_gripper: Callable[[NDArray[np.float64]], NDArray[np.float64]],
        arm: ArmModel,
        calibration: CalibrationPosture,
        rng: np.random.Generator,
        params: OperatorParams | None = None,
        traits: OperatorTraits | None = None,
    ) -> None:
        geometry = TaskGeometry(np.zeros(3), np.asarray(rest_gripper_m, dtype=np.float64))
        super().__init__(geometry, hand_for_gripper, arm, calibration, rng, params, traits)
        self.pointing = task
        # Reach: to the start point; transport: the pointing movement; close: select.
        self._phases = [
            Phase.CALIBRATE, Phase.ALIGN, Phase.ENGAGE, Phase.REACH, Phase.TRANSPORT,
            Phase.CLOSE, Phase.DONE,
        ]  # fmt: skip
        self.selected_s: float | None = None
        self.pointing_start_s: float | None = None

    def criterion_m(self, t: float) -> float:
        if self.phase is Phase.TRANSPORT:
            return self.pointing.width_m / 2 * self._loosening(t)
        return super().criterion_m(t)

    def _glance(self, view: DisplayFrame) -> tuple[Perceived, NDArray[np.float64] | None]:
        # No bowl in this task: the goals below need none.
        seen, _ = super()._glance(view)
        return seen, seen.target_m

    def _goal_gripper(self, seen: Perceived, bowl_m: NDArray[np.float64]) -> NDArray[np.float64]:
        up = np.array([0.0, 0.0, self.pointing.height_m])
        if self.phase is Phase.REACH:
            return self.pointing.start_m + up
        return seen.target_m + up  # the circle as the cloud shows it, centred on by eye

    def _move(self, t: float, hand_delta: NDArray[np.float64], start_s: float) -> None:
        if self.phase is Phase.TRANSPORT and self.pointing_start_s is None:
            self.pointing_start_s = start_s
        super()._move(t, hand_delta, start_s)

    def _advance(self, t: float) -> None:
        if self.phase is Phase.TRANSPORT:
            self.selected_s = t
        super()._advance(t)


class PointingSource(WornSource):
    """A :class:`PointingOperator` wearing the simulated wearable; it stops (None) once the
    operator has selected and the grip has closed, which ends the trial."""

    operator: PointingOperator

    def sample(self, time_s: float, view: DisplayFrame) -> WearableSample | None:
        op = self.operator
        if op.phase is Phase.DONE and time_s >= op._wait_until:
            return None
        return super().sample(time_s, view)

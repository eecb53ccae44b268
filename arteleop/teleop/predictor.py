"""The predictive ghost's source: the robot side's own controller, run on the operator's side.

Under delay the display shows the arm a round trip late. A predictor display (Bejczy, Kim &
Venema, ICRA 1990) draws instead where the commands already sent will put it. Here that is the
robot side's controller itself (reconstruction, hand filter, mapping, IK), a second copy fed
each wearable sample as it is sent, before the network: its joint targets are the ones the
robot will be given once those samples arrive. The site's own commanded targets are no
shortcut: they reach the operator only with the return link's delay, a round trip after the
samples that made them. What the model leaves out is the arm's tracking of its targets
(the trajectory and the position control), about 0.2 s at the task's speeds, and packets the
network will lose or reorder.
"""

from __future__ import annotations

import numpy as np

from arteleop.ar_features import DisplayFrame, PredictedArm
from arteleop.operator import WearableSample
from arteleop.teleop.controller import TeleopController


class CommandPredictor:
    """Where the samples sent so far will put the arm.

    Args:
        controller: A controller built as the robot side's is (same URDF, limits, start
            configuration, operator and settings), with a timer of its own: the trial's stage
            times stay the robot side's.
    """

    def __init__(self, controller: TeleopController) -> None:
        self._control = controller
        self._closure = 0.0
        self.predicted: PredictedArm | None = None
        """The newest prediction; None until the model engages (the arm holds still until
        then, so the frame's own arm is the prediction)."""

    def sent(self, sample: WearableSample) -> None:
        """The operator sent ``sample``: the model receives it at once."""
        self._control.receive(sample.time_s, sample.sensor_quat_wxyz, sample.grip)

    def tick(self, time_s: float, shown: DisplayFrame) -> PredictedArm | None:
        """A control tick of the model at ``time_s`` (s), engaging against the arm that the
        operator's display ``shown`` gives; returns the prediction now."""
        command = self._control.control_tick(shown)
        if command is not None and command.gripper_closure is not None:
            self._closure = command.gripper_closure
        ik = self._control.last_ik
        if not self._control.engaged or ik is None:
            return None
        self.predicted = PredictedArm(
            time_s=time_s,
            arm_q_rad=np.array(ik.q_rad),
            T_base_gripper=self._control.ik.gripper_transform(),
            gripper_closure=self._closure,
        )
        return self.predicted

"""Where the operator's samples come from: a synthetic operator (closed loop) or a recording."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Protocol

import numpy as np
from numpy.typing import ArrayLike, NDArray

from arteleop.ar_features import DisplayFrame
from arteleop.errors import ConfigurationError
from arteleop.operator.live import HandTarget, LiveOperator
from arteleop.operator.output import CALIBRATE, OperatorOutput
from arteleop.operator.simulated.params import OperatorParams
from arteleop.operator.simulated.synthetic import SyntheticOperator
from arteleop.operator.simulated.tasks import PickAndPlace, Task
from arteleop.operator.simulated.traits import OperatorTraits
from arteleop.operator.wearable.arm_model import ArmModel, segment_rotations, segments_for_hand_pose
from arteleop.operator.wearable.posture import CalibrationPosture
from arteleop.operator.wearable.recording import Recording, RecordingInfo
from arteleop.operator.wearable.simulator import WearableConfig, WearableSimulator

if TYPE_CHECKING:
    from arteleop.robot.mapping import MappingConfig
    from arteleop.scene.bowl import BowlSpec


@dataclass(frozen=True)
class WearableSample:
    """One sample as sent by the wearable: IMU quaternions (None if lost) and grip."""

    time_s: float
    sensor_quat_wxyz: NDArray[np.float64] | None
    grip: float
    true_hand_m: NDArray[np.float64] | None = None  # ground truth, for evaluation only


class OperatorSource(Protocol):
    """Gives one sample per control tick; None once the operator has stopped."""

    arm: ArmModel
    calibration: CalibrationPosture

    def sample(self, time_s: float, view: DisplayFrame) -> WearableSample | None: ...


class HandModel(Protocol):
    """Whatever moves the operator's hand: a synthetic operator, or a person through the GUI."""

    def step(self, time_s: float, view: DisplayFrame) -> OperatorOutput: ...


class WornSource:
    """A hand, as a :class:`HandModel` moves it, wearing the simulated wearable: the samples
    are the IMUs' quaternions, with the wearable's errors and losses."""

    def __init__(
        self,
        operator: HandModel,
        rng: np.random.Generator,
        arm: ArmModel,
        calibration: CalibrationPosture,
        wearable: WearableConfig | None = None,
    ) -> None:
        self.arm = arm
        self.calibration = calibration
        self.operator = operator
        # A stream of its own: the sensor errors of a seed stay the same whatever the operator
        # does (how often it looks, under which modality), so conditions share them.
        self.wearable = WearableSimulator(wearable or WearableConfig(), rng.spawn(1)[0])
        self._calibration_segments = segment_rotations(self.calibration.angles)
        self._log: list[tuple[float, NDArray[np.float64] | None, float]] = []

    def sample(self, time_s: float, view: DisplayFrame) -> WearableSample | None:
        out = self.operator.step(time_s, view)
        if out.phase == CALIBRATE:
            segments = self._calibration_segments
        else:
            segments = segments_for_hand_pose(self.arm, out.hand_m, out.R_torso_hand)
        quats = self.wearable.sample(segments)
        self._log.append((time_s, quats, out.grip))
        return WearableSample(time_s, quats, out.grip, out.hand_m)

    def recording(self, subject_id: str) -> Recording:
        """Every sample so far as a recording, the ones the wearable lost marked as lost, so
        that replaying it sends the robot exactly what the live trial sent."""
        n = len(self._log)
        time_s = np.array([t for t, _, _ in self._log])
        lost = np.array([q is None for _, q, _ in self._log], dtype=bool)
        quats = np.full((n, 3, 4), np.nan)
        for i, (_, q, _) in enumerate(self._log):
            if q is not None:
                quats[i] = q
        grip = np.array([g for _, _, g in self._log])
        info = RecordingInfo(self.wearable.config.rate_hz, self.arm, self.calibration, subject_id)
        return Recording.with_lost(time_s, quats, grip, lost, info)


class SyntheticSource(WornSource):
    """A :class:`SyntheticOperator` doing ``task``, wearing the simulated wearable; it stops
    (None) once the operator has finished a task whose last phase ends the trial."""

    operator: SyntheticOperator

    def __init__(
        self,
        task: Task,
        hand_for_gripper: Callable[[NDArray[np.float64]], NDArray[np.float64]],
        rng: np.random.Generator,
        arm: ArmModel | None = None,
        calibration: CalibrationPosture | None = None,
        wearable: WearableConfig | None = None,
        params: OperatorParams | None = None,
        traits: OperatorTraits | None = None,
    ) -> None:
        arm = arm or ArmModel()
        calibration = calibration or CalibrationPosture()
        operator = SyntheticOperator(task, hand_for_gripper, arm, calibration, rng, params, traits)
        super().__init__(operator, rng, arm, calibration, wearable)

    def sample(self, time_s: float, view: DisplayFrame) -> WearableSample | None:
        if self.operator.stopped(time_s):
            return None
        return super().sample(time_s, view)


def check_operator(operator: str, live: bool) -> None:
    """Refuse an operator source that is neither a known name (``synthetic``, and ``live``
    where the view takes live input) nor an existing recording; the message names the
    ``--operator`` option and lists what it takes."""
    names = ("synthetic", "live") if live else ("synthetic",)
    if operator in names or Path(operator).is_file():
        return
    offered = ", 'live' (drive the robot from the page)" if live else ""
    raise ConfigurationError(
        f"--operator {operator}: no such file. Give 'synthetic' (a simulated participant)"
        f"{offered} or the path of a wearable recording's CSV."
    )


class RecordingSource:
    """Replays a recording open loop; it starts with the recording's calibration hold. Samples
    marked lost are sent as lost; gaps a real recording had are sent as the loader filled them."""

    def __init__(self, recording: Recording) -> None:
        self.recording = recording
        self.arm = recording.info.arm
        self.calibration = recording.info.calibration
        self._i = 0

    def sample(self, time_s: float, view: DisplayFrame) -> WearableSample | None:
        rec = self.recording
        t = rec.time_s[0] + time_s
        if t > rec.time_s[-1] + 0.5 / rec.info.rate_hz:
            return None
        while self._i + 1 < len(rec.time_s) and rec.time_s[self._i + 1] <= t + 1e-9:
            self._i += 1
        if rec.lost[self._i]:  # lost in flight when recorded: lost again
            return WearableSample(time_s, None, float("nan"))
        quats = rec.sensor_quat_wxyz[self._i]
        return WearableSample(time_s, quats, float(rec.grip[self._i]))


def synthetic_source(
    bowl: BowlSpec,
    rest_gripper_m: ArrayLike,
    mapping: MappingConfig,
    seed: int,
    params: OperatorParams | None = None,
    traits: OperatorTraits | None = None,
    wearable: WearableConfig | None = None,
    grasp_clearance_m: float = 0.019,
) -> SyntheticSource:
    """A synthetic operator who knows the pick-and-place from instructions and familiarisation.

    Args:
        bowl: The bowl; the operator grasps it at :meth:`BowlSpec.grasp_offset_m`, a rim point
            facing +y, where the open fingers straddle the wall.
        rest_gripper_m: Where the gripper waits at rest, to align the hand on before engaging.
        mapping: The hand-to-gripper mapping the operator was taught.
        seed: Seeds the operator and its wearable (a stream apart from the network's).
        params: The operator's constants; the defaults are docs/explanation/operator-model.md's.
        traits: The person's lasting traits; the default is the median novice.
        grasp_clearance_m: How far off the grasp point the open fingers still straddle the
            bowl's wall (m): the task's tolerance for the grasp.
    """
    task = PickAndPlace(bowl.grasp_offset_m(), rest_gripper_m, grasp_clearance_m)
    return task_source(task, mapping, seed, params, traits, wearable)


def task_source(
    task: Task,
    mapping: MappingConfig,
    seed: int,
    params: OperatorParams | None = None,
    traits: OperatorTraits | None = None,
    wearable: WearableConfig | None = None,
) -> SyntheticSource:
    """A synthetic operator doing ``task``, taught ``mapping`` from its hand to the gripper, and
    seeded by ``seed`` (it and its wearable: a stream apart from the network's)."""
    # Imported here: the robot package loads open3d and pinocchio, which `arteleop.operator`
    # alone (recordings, reconstruction) has no need of.
    from arteleop.robot.mapping import HandToGripper

    rng = np.random.default_rng([seed, 1])
    to_hand = HandToGripper(mapping).hand_position_for
    return SyntheticSource(task, to_hand, rng, wearable=wearable, params=params, traits=traits)


def live_source(target: HandTarget, mapping: MappingConfig, seed: int) -> WornSource:
    """A person driving the hand through ``target`` (a gizmo and a slider in the view), wearing
    the simulated wearable (seeded) so that the robot gets what IMUs would send."""
    from arteleop.robot.mapping import HandToGripper

    arm, calibration = ArmModel(), CalibrationPosture()
    operator = LiveOperator(target, HandToGripper(mapping).hand_position_for, arm, calibration)
    return WornSource(operator, np.random.default_rng([seed, 1]), arm, calibration)

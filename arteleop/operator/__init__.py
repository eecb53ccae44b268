"""The operator: the person, in two rooms, and the sources that feed the loop.

- :mod:`arteleop.operator.simulated`: the simulated participant, what it perceives, decides and
  does, and the tasks it is asked to do.
- :mod:`arteleop.operator.wearable`: what a person wears and what it records: the arm's model,
  the calibration posture, the wearable's IMUs, recordings.
- Here: the sources (``sources``), a person's hand through the view (``live``), what the hand
  does at each tick (``output``) and the minimum-jerk profile both rooms move by.

Their modules were here before 0.4 and are found at their old names, with a warning, through
0.4. The robot side's reading of the wearable (its calibration, the hand's reconstruction) moved
to :mod:`arteleop.teleop` in 0.3; the old names are found here, with a warning, through 0.3.
"""

import importlib
from typing import Any

from arteleop.moved import moved_modules, moved_names
from arteleop.operator.live import HandTarget, LiveOperator
from arteleop.operator.minimum_jerk import minimum_jerk, minimum_jerk_profile
from arteleop.operator.output import OperatorOutput
from arteleop.operator.simulated import (
    ACTIVITIES,
    Action,
    Acuities,
    BowlMemory,
    DisplayGeometry,
    Expertise,
    Goal,
    Judgement,
    MarkMemory,
    MovementScatter,
    OperatorParams,
    OperatorTraits,
    Perceived,
    PerceptionParams,
    PerceptualErrors,
    PhaseRecord,
    PickAndPlace,
    PointingTask,
    SeenOutcomes,
    SyntheticOperator,
    Task,
    TaskPhase,
    TraitDistribution,
    believed_error_scale,
    expected_time_s,
    fixations,
    judgement_sd,
    perceive,
    probability_within,
    reading_sd_m,
    submovement_duration_s,
)
from arteleop.operator.sources import (
    HandModel,
    OperatorSource,
    RecordingSource,
    SyntheticSource,
    WearableSample,
    WornSource,
    check_operator,
    live_source,
    synthetic_source,
    task_source,
)
from arteleop.operator.wearable import (
    COLUMNS,
    SEGMENTS,
    ArmAngles,
    ArmModel,
    CalibrationPosture,
    ImuErrorConfig,
    LoaderConfig,
    LoadReport,
    Recording,
    RecordingInfo,
    SynthesizedRecording,
    WearableConfig,
    WearableSignals,
    hand_from_calibration,
    hand_pose,
    joint_positions,
    load_recording,
    record_hand_motion,
    segment_rotations,
    segments_for_hand_pose,
    sidecar_path,
    simulate_wearable,
    write_recording,
)

__all__ = [
    "ACTIVITIES",
    "COLUMNS",
    "SEGMENTS",
    "Action",
    "Acuities",
    "ArmAngles",
    "ArmModel",
    "BowlMemory",
    "CalibrationPosture",
    "DisplayGeometry",
    "Expertise",
    "Goal",
    "HandModel",
    "HandTarget",
    "ImuErrorConfig",
    "Judgement",
    "LiveOperator",
    "LoadReport",
    "LoaderConfig",
    "MarkMemory",
    "MovementScatter",
    "OperatorOutput",
    "OperatorParams",
    "OperatorSource",
    "OperatorTraits",
    "Perceived",
    "PerceptionParams",
    "PerceptualErrors",
    "PhaseRecord",
    "PickAndPlace",
    "PointingTask",
    "Recording",
    "RecordingInfo",
    "RecordingSource",
    "SeenOutcomes",
    "SynthesizedRecording",
    "SyntheticOperator",
    "SyntheticSource",
    "Task",
    "TaskPhase",
    "TraitDistribution",
    "WearableConfig",
    "WearableSample",
    "WearableSignals",
    "WornSource",
    "believed_error_scale",
    "check_operator",
    "expected_time_s",
    "fixations",
    "hand_from_calibration",
    "hand_pose",
    "joint_positions",
    "judgement_sd",
    "live_source",
    "load_recording",
    "minimum_jerk",
    "minimum_jerk_profile",
    "perceive",
    "probability_within",
    "reading_sd_m",
    "record_hand_motion",
    "segment_rotations",
    "segments_for_hand_pose",
    "sidecar_path",
    "simulate_wearable",
    "submovement_duration_s",
    "synthetic_source",
    "task_source",
    "write_recording",
]

_moved_name = moved_names(
    "arteleop.operator",
    {
        **dict.fromkeys(
            ("HandSample", "HandTrajectory", "SampleStatus", "SensorMounting",
             "StreamingReconstructor", "calibrate", "reconstruct"),
            "arteleop.teleop",
        ),
        "TaskGeometry": "arteleop.operator.simulated.tasks:PickAndPlace",
    },
    until="0.3",
)  # fmt: skip

_MOVED_MODULES = {
    **dict.fromkeys(
        ("acuity", "belief", "bowl_memory", "criterion", "hand", "judging", "look", "mark_memory",
         "own_errors", "params", "perception", "perceptual_errors", "phase_log", "scatter",
         "submovements", "synthetic", "tasks", "traits", "watch"),
        "simulated",
    ),
    **dict.fromkeys(("arm_model", "posture", "recording", "recording_file", "synthesis"),
                    "wearable"),
}  # fmt: skip
"""Modules that moved into a room in 0.4, by name, to their room."""
moved_modules(
    {f"{__name__}.{name}": f"{__name__}.{room}.{name}" for name, room in _MOVED_MODULES.items()},
    until="0.4",
)


def __getattr__(name: str) -> Any:
    if name in _MOVED_MODULES:  # as an attribute, as before 0.4: imported, with the warning
        return importlib.import_module(f"{__name__}.{name}")
    return _moved_name(name)

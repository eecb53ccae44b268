"""The operator: the person and what the person wears. A model of the right arm and the posture
held to calibrate the wearable, the wearable's IMUs and their recordings, the synthetic
participant and what it perceives, and the sources that feed the loop.

The robot side's reading of the wearable (its calibration, the hand's reconstruction) moved to
:mod:`arteleop.teleop` in 0.3; the old names are found here, with a warning, through 0.3.
"""

from arteleop.moved import moved_names
from arteleop.operator.acuity import (
    Acuities,
    DisplayGeometry,
    Judgement,
    fixations,
    judgement_sd,
    reading_sd_m,
)
from arteleop.operator.arm_model import (
    SEGMENTS,
    ArmAngles,
    ArmModel,
    hand_pose,
    joint_positions,
    segment_rotations,
    segments_for_hand_pose,
)
from arteleop.operator.belief import probability_within
from arteleop.operator.bowl_memory import BowlMemory
from arteleop.operator.live import HandTarget, LiveOperator
from arteleop.operator.mark_memory import MarkMemory
from arteleop.operator.minimum_jerk import minimum_jerk, minimum_jerk_profile
from arteleop.operator.output import OperatorOutput
from arteleop.operator.own_errors import SeenOutcomes, believed_error_scale
from arteleop.operator.params import OperatorParams
from arteleop.operator.perception import Perceived, PerceptionParams, perceive
from arteleop.operator.perceptual_errors import PerceptualErrors
from arteleop.operator.phase_log import ACTIVITIES, PhaseRecord
from arteleop.operator.posture import CalibrationPosture, hand_from_calibration
from arteleop.operator.recording import (
    COLUMNS,
    LoaderConfig,
    LoadReport,
    Recording,
    RecordingInfo,
)
from arteleop.operator.recording_file import load_recording, sidecar_path, write_recording
from arteleop.operator.scatter import MovementScatter
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
from arteleop.operator.submovements import expected_time_s, submovement_duration_s
from arteleop.operator.synthesis import SynthesizedRecording, record_hand_motion
from arteleop.operator.synthetic import SyntheticOperator
from arteleop.operator.tasks import (
    Action,
    Goal,
    PickAndPlace,
    PointingTask,
    Task,
    TaskPhase,
)
from arteleop.operator.traits import Expertise, OperatorTraits, TraitDistribution
from arteleop.operator.wearable import (
    ImuErrorConfig,
    WearableConfig,
    WearableSignals,
    simulate_wearable,
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

__getattr__ = moved_names(
    "arteleop.operator",
    {
        **dict.fromkeys(
            ("HandSample", "HandTrajectory", "SampleStatus", "SensorMounting",
             "StreamingReconstructor", "calibrate", "reconstruct"),
            "arteleop.teleop",
        ),
        "TaskGeometry": "arteleop.operator.tasks:PickAndPlace",
    },
    until="0.3",
)  # fmt: skip

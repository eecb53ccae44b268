"""The operator: a wearable IMU model of the right arm, recordings and their reconstruction,
the synthetic operator and the sources that feed the loop."""

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
from arteleop.operator.calibration import SensorMounting, calibrate
from arteleop.operator.live import HandTarget, LiveOperator
from arteleop.operator.minimum_jerk import minimum_jerk, minimum_jerk_profile
from arteleop.operator.perception import (
    BowlMemory,
    Perceived,
    PerceptionParams,
    PerceptualErrors,
    perceive,
)
from arteleop.operator.reconstruction import (
    HandSample,
    HandTrajectory,
    SampleStatus,
    StreamingReconstructor,
    reconstruct,
)
from arteleop.operator.recording import (
    COLUMNS,
    CalibrationPosture,
    LoaderConfig,
    LoadReport,
    Recording,
    RecordingInfo,
    load_recording,
    sidecar_path,
    write_recording,
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
)
from arteleop.operator.submovements import expected_time_s, submovement_duration_s
from arteleop.operator.synthesis import SynthesizedRecording, record_hand_motion
from arteleop.operator.synthetic import (
    OperatorParams,
    Phase,
    SyntheticOperator,
    TaskGeometry,
)
from arteleop.operator.traits import Expertise, OperatorTraits, TraitDistribution
from arteleop.operator.wearable import (
    ImuErrorConfig,
    WearableConfig,
    WearableSignals,
    simulate_wearable,
)

__all__ = [
    "COLUMNS",
    "SEGMENTS",
    "ArmAngles",
    "ArmModel",
    "BowlMemory",
    "CalibrationPosture",
    "Expertise",
    "HandModel",
    "HandSample",
    "HandTarget",
    "HandTrajectory",
    "ImuErrorConfig",
    "LiveOperator",
    "LoadReport",
    "LoaderConfig",
    "OperatorParams",
    "OperatorSource",
    "OperatorTraits",
    "Perceived",
    "PerceptionParams",
    "PerceptualErrors",
    "Phase",
    "Recording",
    "RecordingInfo",
    "RecordingSource",
    "SampleStatus",
    "SensorMounting",
    "StreamingReconstructor",
    "SynthesizedRecording",
    "SyntheticOperator",
    "SyntheticSource",
    "TaskGeometry",
    "TraitDistribution",
    "WearableConfig",
    "WearableSample",
    "WearableSignals",
    "WornSource",
    "calibrate",
    "check_operator",
    "expected_time_s",
    "hand_pose",
    "joint_positions",
    "live_source",
    "load_recording",
    "minimum_jerk",
    "minimum_jerk_profile",
    "perceive",
    "probability_within",
    "reconstruct",
    "record_hand_motion",
    "segment_rotations",
    "segments_for_hand_pose",
    "sidecar_path",
    "simulate_wearable",
    "submovement_duration_s",
    "synthetic_source",
    "write_recording",
]

"""What a person wears and what it records: the right arm's model
(``arm_model``) and the posture held to calibrate (``posture``), the wearable's IMUs and pinch
sensor (``simulator``), the recordings of them and their files (``recording``,
``recording_file``), and recordings synthesised from a hand's motion (``synthesis``).

Before 0.4 the simulator was the module ``arteleop.operator.wearable``: its names are found here.
"""

from arteleop.operator.wearable.arm_model import (
    SEGMENTS,
    ArmAngles,
    ArmModel,
    hand_pose,
    joint_positions,
    segment_rotations,
    segments_for_hand_pose,
)
from arteleop.operator.wearable.posture import (
    CalibrationPosture,
    hand_from_calibration,
)
from arteleop.operator.wearable.recording import (
    COLUMNS,
    LoaderConfig,
    LoadReport,
    Recording,
    RecordingInfo,
)
from arteleop.operator.wearable.recording_file import (
    load_recording,
    sidecar_path,
    write_recording,
)
from arteleop.operator.wearable.simulator import (
    BLOCK_SAMPLES,
    ImuErrorConfig,
    WearableConfig,
    WearableSignals,
    WearableSimulator,
    simulate_wearable,
)
from arteleop.operator.wearable.synthesis import (
    SynthesizedRecording,
    record_hand_motion,
)

__all__ = [
    "BLOCK_SAMPLES",
    "COLUMNS",
    "SEGMENTS",
    "ArmAngles",
    "ArmModel",
    "CalibrationPosture",
    "ImuErrorConfig",
    "LoadReport",
    "LoaderConfig",
    "Recording",
    "RecordingInfo",
    "SynthesizedRecording",
    "WearableConfig",
    "WearableSignals",
    "WearableSimulator",
    "hand_from_calibration",
    "hand_pose",
    "joint_positions",
    "load_recording",
    "record_hand_motion",
    "segment_rotations",
    "segments_for_hand_pose",
    "sidecar_path",
    "simulate_wearable",
    "write_recording",
]

"""Wearable recordings: one CSV row per sample plus a JSON sidecar with the same stem.

CSV columns, in this order (header line required)::

    time_s, upper_arm_qw, upper_arm_qx, upper_arm_qy, upper_arm_qz,
    forearm_qw, ..., forearm_qz, hand_qw, ..., hand_qz, grip

Quaternions are each IMU's orientation in its earth frame, (w, x, y, z), unit length. ``grip`` is
0 (open) to 1 (pinched). Version 2: a sample the wearable lost in flight is a row with its time
and every other cell empty, so that a replay loses it too. The sidecar gives the rate, the arm's
segment lengths, the calibration posture held at the start, the subject id and the units. See
docs/reference/recording-format.md. Reading and writing the files is
:mod:`arteleop.operator.wearable.recording_file`'s.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray
from scipy.spatial.transform import Rotation, Slerp

from arteleop.checks import Bounds, check_fields
from arteleop.errors import ConfigurationError, RecordingError
from arteleop.moved import moved_names
from arteleop.operator.wearable.arm_model import SEGMENTS, ArmModel
from arteleop.operator.wearable.posture import CalibrationPosture

COLUMNS: tuple[str, ...] = (
    "time_s",
    *(f"{s}_q{c}" for s in SEGMENTS for c in "wxyz"),
    "grip",
)
FORMAT_NAME = "arteleop-wearable-recording"
FORMAT_VERSION = 2
"""2: lost samples may be marked (a row with the time only). Version 1 files read unchanged."""
READ_VERSIONS = (1, 2)
UNITS = {
    "time_s": "s",
    "quaternions": "unit quaternion (w, x, y, z): IMU orientation in the earth frame",
    "grip": "0 open .. 1 pinched",
    "lengths": "m",
    "angles": "rad",
}


RATE_BOUNDS_HZ = (10.0, 1000.0)
"""Sample rates a wearable recording may have: the IMUs of the field run at 50-400 Hz (the
original's at 100 Hz)."""


@dataclass(frozen=True)
class RecordingInfo:
    """The sidecar's content."""

    rate_hz: float = 100.0
    arm: ArmModel = field(default_factory=ArmModel)
    calibration: CalibrationPosture = field(default_factory=CalibrationPosture)
    subject_id: str = "synthetic"

    def __post_init__(self) -> None:
        check_fields(self, {"rate_hz": Bounds(*RATE_BOUNDS_HZ, "Hz, an IMU's sample rate")})


@dataclass(frozen=True)
class LoadReport:
    """What the loader repaired within its tolerances.

    Attributes:
        filled_samples: Samples inserted by slerp into short gaps.
        gaps: Number of gaps filled.
        renormalized: Quaternions rescaled to unit length.
        lost_samples: Rows marking a sample the wearable lost (version 2).
    """

    filled_samples: int = 0
    gaps: int = 0
    renormalized: int = 0
    lost_samples: int = 0


@dataclass(frozen=True)
class Recording:
    """A wearable recording. Arrays are read-only.

    Attributes:
        time_s: (N,) strictly increasing sample times (s).
        sensor_quat_wxyz: (N, 3, 4) IMU orientations in the earth frame.
        grip: (N,) pinch grip, 0 open .. 1 pinched.
        info: Rate, arm, calibration posture, subject.
        report: What loading repaired (all zeros for recordings made in memory).
        lost: (N,) samples the wearable lost in flight. Their values are filled by slerp (grip
            linearly) from the samples around them, for whole-recording use; a replay sends them
            as lost, as the live wearable did. None: nothing lost.
    """

    time_s: NDArray[np.float64]
    sensor_quat_wxyz: NDArray[np.float64]
    grip: NDArray[np.float64]
    info: RecordingInfo
    report: LoadReport = field(default_factory=LoadReport)
    lost: NDArray[np.bool_] | None = None

    def __post_init__(self) -> None:
        n = len(self.time_s)
        lost = np.zeros(n, bool) if self.lost is None else self.lost
        if (
            np.shape(self.sensor_quat_wxyz) != (n, 3, 4)
            or np.shape(self.grip) != (n,)
            or np.shape(lost) != (n,)
        ):
            raise ConfigurationError(
                f"Recording arrays disagree: time {np.shape(self.time_s)}, quaternions "
                f"{np.shape(self.sensor_quat_wxyz)} (need (N, 3, 4)), grip {np.shape(self.grip)}, "
                f"lost {np.shape(lost)}"
            )
        for name in ("time_s", "sensor_quat_wxyz", "grip"):
            arr = np.array(getattr(self, name), dtype=np.float64)
            arr.setflags(write=False)
            object.__setattr__(self, name, arr)
        lost = np.array(lost, dtype=bool)
        lost.setflags(write=False)
        object.__setattr__(self, "lost", lost)

    @classmethod
    def with_lost(
        cls,
        time_s: NDArray[np.float64],
        sensor_quat_wxyz: NDArray[np.float64],
        grip: NDArray[np.float64],
        lost: NDArray[np.bool_],
        info: RecordingInfo,
    ) -> Recording:
        """A recording whose ``lost`` samples hold no values yet: they are filled from the
        samples around them."""
        quats, grip = fill_lost(time_s, sensor_quat_wxyz, grip, lost)
        return cls(time_s, quats, grip, info, lost=lost)

    @property
    def duration_s(self) -> float:
        return float(self.time_s[-1] - self.time_s[0]) if len(self.time_s) else 0.0


@dataclass(frozen=True)
class LoaderConfig:
    """Tolerances of :func:`load_recording`.

    Attributes:
        unit_norm_tolerance: Quaternions whose norm is within this of 1 are renormalised; others
            are rejected.
        max_gap_s: Gaps up to this long are filled by slerp; longer ones are an error. A gap is
            the time between two consecutive rows.
        rate_tolerance: Allowed relative difference between the sidecar's rate and the median
            sample interval.
    """

    unit_norm_tolerance: float = 0.01
    max_gap_s: float = 0.1
    rate_tolerance: float = 0.05


def fill_lost(
    time_s: NDArray[np.float64],
    quats: NDArray[np.float64],
    grip: NDArray[np.float64],
    lost: NDArray[np.bool_],
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Quaternions by slerp and grip linearly at the ``lost`` samples, from the kept ones (held
    before the first and after the last kept sample)."""
    quats, grip = np.array(quats, dtype=np.float64), np.array(grip, dtype=np.float64)
    lost = np.asarray(lost, dtype=bool)
    if not lost.any():
        return quats, grip
    kept = ~lost
    if kept.sum() < 2:
        raise RecordingError("a recording needs at least 2 samples that were not lost")
    t_kept = time_s[kept]
    t_lost = np.clip(time_s[lost], t_kept[0], t_kept[-1])
    for k in range(3):
        slerp = Slerp(t_kept, Rotation.from_quat(quats[kept, k], scalar_first=True))
        quats[lost, k] = slerp(t_lost).as_quat(scalar_first=True)
    grip[lost] = np.interp(t_lost, t_kept, grip[kept])
    return quats, grip


__getattr__ = moved_names(
    "arteleop.operator.recording",
    dict.fromkeys(
        ("load_recording", "sidecar_path", "write_recording"),
        "arteleop.operator.wearable.recording_file",
    ),
    until="0.3",
)

"""Reading and writing wearable recordings: the CSV and its JSON sidecar
(docs/reference/recording-format.md), loaded strictly, each problem named by file, line and
column."""

from __future__ import annotations

import csv
import io
import json
import math
from dataclasses import asdict
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy.spatial.transform import Rotation, Slerp

from arteleop.errors import ConfigurationError, RecordingError
from arteleop.files import write_atomic
from arteleop.operator.wearable.arm_model import SEGMENTS, ArmAngles, ArmModel
from arteleop.operator.wearable.posture import CalibrationPosture
from arteleop.operator.wearable.recording import (
    COLUMNS,
    FORMAT_NAME,
    FORMAT_VERSION,
    READ_VERSIONS,
    UNITS,
    LoaderConfig,
    LoadReport,
    Recording,
    RecordingInfo,
    fill_lost,
)


def sidecar_path(csv_path: Path) -> Path:
    """The JSON sidecar that goes with ``csv_path``."""
    return csv_path.with_suffix(".json")


def write_recording(recording: Recording, csv_path: Path) -> None:
    """Write the CSV and its sidecar, each whole or not at all (through a temporary file and a
    rename: a full disk leaves the old files); loading them gives the same numbers back
    exactly. Raises ``OSError`` where the files cannot be written."""
    csv_path = Path(csv_path)
    q = recording.sensor_quat_wxyz.reshape(len(recording.time_s), 12)
    lost_row = [""] * (len(COLUMNS) - 1)
    buffer = io.StringIO()
    writer = csv.writer(buffer)
    writer.writerow(COLUMNS)
    for t, quats, g, lost in zip(recording.time_s, q, recording.grip, recording.lost, strict=True):
        values = lost_row if lost else [*(repr(float(v)) for v in quats), repr(float(g))]
        writer.writerow([repr(float(t)), *values])
    info = recording.info
    sidecar = {
        "format": FORMAT_NAME,
        "version": FORMAT_VERSION,
        "subject_id": info.subject_id,
        "rate_hz": info.rate_hz,
        "arm": asdict(info.arm),
        "calibration_posture": {
            "angles_rad": asdict(info.calibration.angles),
            "torso_heading_rad": info.calibration.torso_heading_rad,
            "hold_s": info.calibration.hold_s,
        },
        "units": UNITS,
    }
    write_atomic(csv_path, buffer.getvalue())
    write_atomic(sidecar_path(csv_path), json.dumps(sidecar, indent=2) + "\n")


def load_recording(csv_path: Path, config: LoaderConfig | None = None) -> Recording:
    """Load and check a recording; raise :class:`RecordingError` naming the file, line and value."""
    config = config or LoaderConfig()
    csv_path = Path(csv_path)
    if not csv_path.is_file():
        raise RecordingError(f"{csv_path}: no such file")
    if csv_path.stat().st_size == 0:
        raise RecordingError(
            f"{csv_path} is empty: a recording has a header line and at least 2 samples "
            "(docs/reference/recording-format.md)."
        )
    info = _load_sidecar(sidecar_path(csv_path), csv_path)
    rows: list[list[float]] = []
    lines: list[int] = []
    lost: list[bool] = []
    renormalized = 0
    with csv_path.open(newline="") as f:
        reader = csv.reader(f)
        header = [h.strip() for h in next(reader, [])]
        _check_header(csv_path, header)
        for row in reader:
            line = reader.line_num
            if not row or all(not c.strip() for c in row):
                continue
            marked = len(row) == len(COLUMNS) and all(not c.strip() for c in row[1:])
            if marked:  # version 2: the wearable lost this sample
                t = _parse_number(csv_path, line, "time_s", row[0])
                values, fixed = [t] + [math.nan] * (len(COLUMNS) - 1), 0
            else:
                values, fixed = _parse_row(csv_path, line, row, config)
            renormalized += fixed
            if rows and values[0] <= rows[-1][0]:
                raise RecordingError(
                    f"{csv_path}, line {line}, column time_s: {values[0]!r} s does not come after "
                    f"the previous sample's {rows[-1][0]!r} s; time must increase."
                )
            rows.append(values)
            lines.append(line)
            lost.append(marked)
    if len(rows) - sum(lost) < 2:
        raise RecordingError(
            f"{csv_path}: {len(rows) - sum(lost)} sample(s); a recording needs at least 2."
        )
    data = np.array(rows)
    time, quats, grip = data[:, 0], data[:, 1:13].reshape(-1, 3, 4), data[:, 13]
    _check_rate(csv_path, time, info.rate_hz, config)
    quats, grip = fill_lost(time, quats, grip, np.array(lost))
    recorded_time = time
    time, quats, grip, filled, gaps = _fill_gaps(
        csv_path, lines, time, quats, grip, info.rate_hz, config
    )
    marks = np.zeros(len(time), bool)
    marks[np.isin(time, recorded_time)] = lost  # samples filled into gaps are not marked lost
    report = LoadReport(filled, gaps, renormalized, int(sum(lost)))
    return Recording(time, quats, grip, info, report, marks)


def _check_header(path: Path, header: list[str]) -> None:
    if header == list(COLUMNS):
        return
    missing = [c for c in COLUMNS if c not in header]
    unknown = [c for c in header if c not in COLUMNS]
    if missing or unknown:
        raise RecordingError(
            f"{path}, line 1 (header): missing columns {missing}, unknown columns {unknown}. "
            f"Expected exactly: {', '.join(COLUMNS)}"
        )
    raise RecordingError(
        f"{path}, line 1 (header): columns are out of order. Expected: {', '.join(COLUMNS)}"
    )


def _parse_number(path: Path, line: int, column: str, text: str) -> float:
    try:
        v = float(text)
    except ValueError:
        raise RecordingError(
            f"{path}, line {line}, column {column}: {text.strip()!r} is not a number"
        ) from None
    if not math.isfinite(v):
        raise RecordingError(
            f"{path}, line {line}, column {column}: {text.strip()!r}; expected a finite number"
        )
    return v


def _parse_row(
    path: Path, line: int, row: list[str], config: LoaderConfig
) -> tuple[list[float], int]:
    if len(row) != len(COLUMNS):
        raise RecordingError(
            f"{path}, line {line}: {len(row)} fields, expected {len(COLUMNS)}: {', '.join(COLUMNS)}"
        )
    values = [
        _parse_number(path, line, name, text) for name, text in zip(COLUMNS, row, strict=True)
    ]
    fixed = 0
    for k, seg in enumerate(SEGMENTS):
        q = values[1 + 4 * k : 5 + 4 * k]
        norm = math.sqrt(sum(c * c for c in q))
        if abs(norm - 1.0) > config.unit_norm_tolerance:
            raise RecordingError(
                f"{path}, line {line}, columns {seg}_qw..{seg}_qz: quaternion {q} has norm "
                f"{norm:.4f}; expected unit length within {config.unit_norm_tolerance}"
            )
        if abs(norm - 1.0) > 1e-12:  # beyond float rounding, so exact files stay exact
            values[1 + 4 * k : 5 + 4 * k] = [c / norm for c in q]
            fixed += 1
    if not 0.0 <= values[-1] <= 1.0:
        raise RecordingError(
            f"{path}, line {line}, column grip: {values[-1]!r}; expected 0 (open) to 1 (pinched)"
        )
    return values, fixed


def _check_rate(
    path: Path, time: NDArray[np.float64], rate_hz: float, config: LoaderConfig
) -> None:
    measured = 1.0 / float(np.median(np.diff(time)))
    if abs(measured / rate_hz - 1.0) > config.rate_tolerance:
        raise RecordingError(
            f"{path}: samples come at {measured:.2f} Hz but {sidecar_path(path).name} says "
            f"rate_hz = {rate_hz}; correct the sidecar."
        )


def _fill_gaps(
    path: Path,
    lines: list[int],
    time: NDArray[np.float64],
    quats: NDArray[np.float64],
    grip: NDArray[np.float64],
    rate_hz: float,
    config: LoaderConfig,
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], int, int]:
    dt = 1.0 / rate_hz
    steps = np.diff(time)
    gaps = np.flatnonzero(steps > 1.5 * dt)
    if len(gaps) == 0:
        return time, quats, grip, 0, 0
    for i in gaps:
        if steps[i] > config.max_gap_s + 1e-9:
            raise RecordingError(
                f"{path}, line {lines[i + 1]}: time jumps from {float(time[i])!r} s to "
                f"{float(time[i + 1])!r} s, a gap of {steps[i] * 1000:.0f} ms; gaps up to "
                f"{config.max_gap_s * 1000:.0f} ms are filled, longer ones mean the wearable "
                "lost contact."
            )
    new_t = [time[: gaps[0] + 1]]
    for j, i in enumerate(gaps):
        n_missing = round(steps[i] / dt) - 1
        new_t.append(time[i] + dt * np.arange(1, n_missing + 1))
        end = gaps[j + 1] + 1 if j + 1 < len(gaps) else len(time)
        new_t.append(time[i + 1 : end])
    t_all = np.concatenate(new_t)
    q_all = np.empty((len(t_all), 3, 4))
    for k in range(3):
        slerp = Slerp(time, Rotation.from_quat(quats[:, k], scalar_first=True))
        q_all[:, k] = slerp(t_all).as_quat(scalar_first=True)
    # Keep the recorded samples bit for bit; only the inserted ones are interpolated.
    recorded = np.isin(t_all, time)
    q_all[recorded] = quats
    g_all = np.interp(t_all, time, grip)
    return t_all, q_all, g_all, int(len(t_all) - len(time)), len(gaps)


def _load_sidecar(path: Path, csv_path: Path) -> RecordingInfo:
    if not path.is_file():
        raise RecordingError(
            f"{csv_path}: its sidecar {path.name} is missing; every recording needs one (rate, "
            "segment lengths, calibration posture, subject id, units)."
        )
    try:
        data: dict[str, Any] = json.loads(path.read_text(encoding="utf-8"))
    except json.JSONDecodeError as err:
        raise RecordingError(f"{path}, line {err.lineno}: not valid JSON ({err.msg})") from None
    except (OSError, UnicodeDecodeError) as err:
        raise RecordingError(f"{path}: cannot be read ({err})") from None
    if not isinstance(data, dict):
        raise RecordingError(
            f"{path}: a JSON {type(data).__name__}; expected an object with format, version, "
            "rate_hz, arm, calibration_posture, subject_id and units "
            "(docs/reference/recording-format.md)"
        )
    if data.get("format") != FORMAT_NAME or data.get("version") not in READ_VERSIONS:
        raise RecordingError(
            f"{path}: format {data.get('format')!r} version {data.get('version')!r}; expected "
            f"{FORMAT_NAME!r} version {' or '.join(map(str, READ_VERSIONS))}"
        )
    try:
        posture = data["calibration_posture"]
        return RecordingInfo(
            rate_hz=float(data["rate_hz"]),
            arm=ArmModel(
                **{k: tuple(v) if isinstance(v, list) else float(v) for k, v in data["arm"].items()}
            ),
            calibration=CalibrationPosture(
                angles=ArmAngles(**{k: float(v) for k, v in posture["angles_rad"].items()}),
                torso_heading_rad=float(posture["torso_heading_rad"]),
                hold_s=float(posture["hold_s"]),
            ),
            subject_id=str(data["subject_id"]),
        )
    except KeyError as err:
        raise RecordingError(f"{path}: missing field {err}") from None
    except (TypeError, ValueError, AttributeError, ConfigurationError) as err:
        raise RecordingError(f"{path}: {err}") from None

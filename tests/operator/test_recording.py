"""The recording format: exact round trips, and one broken file per failure mode."""

import json
from pathlib import Path

import numpy as np
import pytest

from arteleop.errors import RecordingError
from arteleop.operator import (
    COLUMNS,
    ImuErrorConfig,
    Recording,
    load_recording,
    sidecar_path,
    write_recording,
)
from tests.operator.motions import reach_and_return


@pytest.fixture
def good(tmp_path: Path) -> Path:
    path = tmp_path / "good.csv"
    write_recording(reach_and_return(errors=ImuErrorConfig.ideal()).recording, path)
    return path


def _edit_line(path: Path, line: int, fn) -> Path:
    lines = path.read_text().splitlines()
    lines[line - 1] = fn(lines[line - 1])
    path.write_text("\n".join(lines) + "\n")
    return path


def _set_field(path: Path, line: int, column: str, value: str) -> Path:
    i = COLUMNS.index(column)

    def change(text: str) -> str:
        fields = text.split(",")
        fields[i] = value
        return ",".join(fields)

    return _edit_line(path, line, change)


def test_header_is_exactly_the_documented_one(good: Path) -> None:
    header = good.read_text().splitlines()[0]
    assert header.split(",")[:5] == [
        "time_s",
        "upper_arm_qw",
        "upper_arm_qx",
        "upper_arm_qy",
        "upper_arm_qz",
    ]
    assert header.split(",")[-1] == "grip" and len(header.split(",")) == 14
    meta = json.loads(sidecar_path(good).read_text())
    assert meta["rate_hz"] == 100.0 and meta["units"]["time_s"] == "s"
    assert set(meta) >= {"subject_id", "arm", "calibration_posture", "units"}


def test_round_trip_is_exact(tmp_path: Path) -> None:
    rec = reach_and_return(seed=3, errors=ImuErrorConfig(drop_probability=0.0)).recording
    write_recording(rec, tmp_path / "a.csv")
    back = load_recording(tmp_path / "a.csv")
    assert np.array_equal(back.time_s, rec.time_s)
    assert np.array_equal(back.sensor_quat_wxyz, rec.sensor_quat_wxyz)
    assert np.array_equal(back.grip, rec.grip)
    assert back.info == rec.info


def test_same_seed_same_files(tmp_path: Path) -> None:
    for name, seed in (("a", 5), ("b", 5), ("c", 6)):
        write_recording(reach_and_return(seed=seed).recording, tmp_path / f"{name}.csv")
    assert (tmp_path / "a.csv").read_bytes() == (tmp_path / "b.csv").read_bytes()
    assert (tmp_path / "a.csv").read_bytes() != (tmp_path / "c.csv").read_bytes()


def test_short_gap_is_filled_and_counted(good: Path) -> None:
    lines = good.read_text().splitlines()
    del lines[200:205]  # five samples, 60 ms between the neighbours
    good.write_text("\n".join(lines) + "\n")
    rec = load_recording(good)
    assert (rec.report.filled_samples, rec.report.gaps) == (5, 1)
    np.testing.assert_allclose(np.diff(rec.time_s), 0.01, atol=1e-9)
    np.testing.assert_allclose(np.linalg.norm(rec.sensor_quat_wxyz, axis=2), 1.0, atol=1e-12)


def test_small_norm_drift_is_renormalised(good: Path) -> None:
    _set_field(
        good, 10, "hand_qw", repr(float(good.read_text().splitlines()[9].split(",")[9]) * 1.004)
    )
    rec = load_recording(good)
    assert rec.report.renormalized == 1
    assert np.linalg.norm(rec.sensor_quat_wxyz[8, 2]) == pytest.approx(1.0, abs=1e-12)


@pytest.mark.parametrize(
    ("breaker", "message"),
    [
        (
            lambda p: _set_field(p, 7, "forearm_qx", "abc"),
            r"line 7, column forearm_qx: 'abc' is not a number",
        ),
        (
            lambda p: _set_field(p, 8, "grip", "nan"),
            r"line 8, column grip: 'nan'; expected a finite number",
        ),
        (
            lambda p: _set_field(p, 9, "grip", "1.5"),
            r"line 9, column grip: 1.5; expected 0 \(open\) to 1",
        ),
        (
            lambda p: _set_field(p, 12, "time_s", "0.0"),
            r"line 12, column time_s: 0.0 s does not come after",
        ),
        (
            lambda p: _set_field(p, 15, "upper_arm_qw", "3.0"),
            r"line 15, columns upper_arm_qw..upper_arm_qz: .* norm",
        ),
        (lambda p: _edit_line(p, 20, lambda t: t + ",0.5"), r"line 20: 15 fields, expected 14"),
        (
            lambda p: _edit_line(p, 1, lambda t: t.replace("hand_qz", "hand_gz")),
            r"line 1 \(header\): missing columns \['hand_qz'\], unknown columns \['hand_gz'\]",
        ),
        (
            lambda p: _edit_line(p, 1, lambda t: t.replace(",grip", "")),
            r"missing columns \['grip'\]",
        ),
    ],
)
def test_each_broken_file_names_line_and_value(good: Path, breaker, message: str) -> None:
    breaker(good)
    with pytest.raises(RecordingError, match=message) as info:
        load_recording(good)
    assert str(good) in str(info.value)


def test_long_gap_is_an_error(good: Path) -> None:
    lines = good.read_text().splitlines()
    del lines[300:320]  # 200 ms lost
    good.write_text("\n".join(lines) + "\n")
    with pytest.raises(
        RecordingError, match=r"line 301: time jumps .* a gap of 210 ms; gaps up to 100 ms"
    ):
        load_recording(good)


def test_missing_or_broken_sidecar(good: Path) -> None:
    side = sidecar_path(good)
    side.write_text('{"format": "arteleop-wearable-recording", "version": 1,')
    with pytest.raises(RecordingError, match=r"good.json, line 1: not valid JSON"):
        load_recording(good)
    side.unlink()
    with pytest.raises(RecordingError, match=r"its sidecar good.json is missing"):
        load_recording(good)


def test_sidecar_rate_must_match_the_samples(good: Path) -> None:
    side = sidecar_path(good)
    meta = json.loads(side.read_text())
    meta["rate_hz"] = 50.0
    side.write_text(json.dumps(meta))
    with pytest.raises(
        RecordingError, match=r"samples come at 100.00 Hz but good.json says rate_hz = 50.0"
    ):
        load_recording(good)


def test_lost_samples_are_marked_and_come_back_marked(tmp_path: Path) -> None:
    rec = reach_and_return(errors=ImuErrorConfig.ideal()).recording
    lost = np.zeros(len(rec.time_s), bool)
    lost[[200, 201, 350]] = True
    unknown = np.where(lost[:, None, None], np.nan, rec.sensor_quat_wxyz)  # never received
    write_recording(
        Recording.with_lost(rec.time_s, unknown, rec.grip, lost, rec.info), tmp_path / "r.csv"
    )
    row = (tmp_path / "r.csv").read_text().splitlines()[1 + 200]
    assert row == f"{float(rec.time_s[200])!r}" + "," * 13
    back = load_recording(tmp_path / "r.csv")
    np.testing.assert_array_equal(back.lost, lost)
    assert (back.report.lost_samples, back.report.gaps) == (3, 0)
    np.testing.assert_array_equal(back.sensor_quat_wxyz[~lost], rec.sensor_quat_wxyz[~lost])
    # Filled by slerp from their neighbours: within 0.003 (about 0.2 deg) of the smooth motion.
    np.testing.assert_allclose(back.sensor_quat_wxyz[lost], rec.sensor_quat_wxyz[lost], atol=3e-3)

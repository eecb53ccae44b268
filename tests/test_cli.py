from pathlib import Path

import cv2
import numpy as np
import open3d as o3d
import pytest

from arteleop.cli import main


def test_scene_command_writes_the_three_files(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["scene", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    rgb = cv2.imread(str(tmp_path / "rgb.png"))
    depth = cv2.imread(str(tmp_path / "depth.png"), cv2.IMREAD_UNCHANGED)
    cloud = o3d.io.read_point_cloud(str(tmp_path / "cloud.ply"))
    assert rgb.shape == (480, 640, 3)
    vis = cv2.imread(str(tmp_path / "depth_vis.png"))
    assert vis.shape == (480, 640, 3)
    assert (vis[depth == 0] == 0).all()  # no return: black
    assert (vis[depth > 0].max(axis=1) > 100).mean() > 0.99  # returns: in colour
    assert depth.dtype == np.uint16 and depth.shape == (480, 640)
    valid = depth[depth > 0]
    assert 800 <= valid.min() and valid.max() <= 4000  # millimetres, in the sensor's range
    assert len(cloud.points) == np.count_nonzero(depth)
    z = np.asarray(cloud.points)[:, 2]
    assert np.median(z) == pytest.approx(-0.2, abs=0.01)  # mostly table top, base frame, metres
    error_mm = float(out.split("tracking error")[1].split("mm")[0])
    assert error_mm <= 5.0


def test_cli_reports_bad_options(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as exit_info:
        main(["scene", "--width-px", "many"])
    assert exit_info.value.code != 0
    assert "many" in capsys.readouterr().err


def test_operator_check_summarises_a_valid_recording(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from arteleop.operator import ImuErrorConfig, write_recording
    from tests.operator.motions import reach_and_return

    syn = reach_and_return(errors=ImuErrorConfig.ideal())
    write_recording(syn.recording, tmp_path / "rec.csv")
    assert main(["operator", "check", str(tmp_path / "rec.csv")]) == 0
    out = capsys.readouterr().out
    assert "duration      5.00 s, 501 samples" in out
    assert "gaps          0 filled" in out
    # Ideal sensors: the filtered reconstruction's path is the true path of the smooth motion
    # (1.5 s out and 1.5 s back, after the move from the calibration posture).
    true_path = np.linalg.norm(np.diff(syn.hand_m, axis=0), axis=1).sum()
    shown = float(out.split("hand path")[1].split("m (")[0])
    assert shown == pytest.approx(true_path, rel=0.01)


def test_operator_check_fails_on_an_invalid_recording(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from arteleop.operator import write_recording
    from tests.operator.motions import reach_and_return

    path = tmp_path / "rec.csv"
    write_recording(reach_and_return().recording, path)
    lines = path.read_text().splitlines()
    lines[3] = ",".join([*lines[3].split(",")[:13], "2.0"])  # grip of the sample on line 4
    path.write_text("\n".join(lines) + "\n")
    assert main(["operator", "check", str(path)]) == 2
    assert "line 4, column grip: 2.0; expected 0 (open) to 1 (pinched)" in capsys.readouterr().err


def test_calibrate_prints_every_method_and_writes_the_graph(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from arteleop.frames import EdgeKind, TransformGraph

    out = tmp_path / "frames" / "calibration.json"
    assert main(["calibrate", "--poses", "6", "--out", str(out)]) == 0
    text = capsys.readouterr().out
    rows = [line.split(" | ") for line in text.splitlines() if line.startswith("| ")][2:]
    methods = [r[0].lstrip("| ") for r in rows]
    assert methods[:2] == ["helper", "tsai"] and methods[-1].endswith(" + refined")
    assert len(methods) == 9
    graph = TransformGraph.load(out)
    edge = graph.edge("base", "head_camera")
    assert edge.kind is EdgeKind.CALIBRATION and edge.transform.covariance is not None
    # The site's other frames come with it: the robot at rest, the table and the markers.
    from arteleop.robot import GRIPPER_FRAME
    from arteleop.scene import Workspace

    assert {GRIPPER_FRAME, "table", "start_marker"} <= set(graph.frames)
    np.testing.assert_array_equal(graph.T("base", "target_marker")[:3, 3], Workspace().target_m)
    # The file holds the refined estimate that the last row scores.
    refined_mm = float(rows[-1][2])
    assert refined_mm < 20.0


def test_calibrate_measures_a_mis_set_camera_and_brings_it_back(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    args = ["--camera-offset-mm", "20", "0", "0", "--camera-offset-deg", "0", "1", "0"]
    assert main(["calibrate", "--poses", "8", "--out", str(tmp_path / "c.json"), *args]) == 0
    rows = {
        r[0].lstrip("| "): r
        for r in (line.split(" | ") for line in capsys.readouterr().out.splitlines())
        if len(r) == 7
    }
    given = rows["registration given (--camera-offset-*)"]
    assert (given[2], given[3]) == ("20.0", "1.00")
    refined = next(r for name, r in rows.items() if name.endswith(" + refined"))
    assert float(refined[5]) < float(given[5]) / 5  # co-location (px): calibration fixes it


def test_calibrate_refuses_too_few_poses(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["calibrate", "--poses", "2"]) == 2
    assert capsys.readouterr().err == (
        "arteleop: error: --poses 2: hand-eye calibration needs at least 3 poses\n"
    )


def test_a_camera_graph_file_sets_the_registration(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], site
) -> None:
    """A graph whose camera sits 25 mm off the true pose (along base x) moves the tracked bowl
    by that much; a graph without the camera's edge is refused, naming the file."""
    from arteleop.frames import EdgeKind, TransformGraph

    T = site.camera.T_base_camera.copy()
    T[0, 3] += 0.025
    graph = TransformGraph()
    graph.set("base", "head_camera", T, EdgeKind.CALIBRATION)
    graph.save(tmp_path / "g.json")
    assert (
        main(["scene", "--out", str(tmp_path / "s"), "--camera-graph", str(tmp_path / "g.json")])
        == 0
    )
    out = capsys.readouterr().out
    assert float(out.split("tracking error")[1].split("mm")[0]) == pytest.approx(25.0, abs=4.0)
    TransformGraph().save(tmp_path / "empty.json")
    assert main(["scene", "--camera-graph", str(tmp_path / "empty.json")]) == 2
    assert capsys.readouterr().err == (
        f"arteleop: error: --camera-graph {tmp_path / 'empty.json'}: no frame 'base' in the graph; "
        "its frames are []. 'arteleop calibrate' writes such a file, with the edge base -> "
        "head_camera.\n"
    )


def test_a_trial_with_a_mis_registered_camera_reports_its_colocation_error(
    capsys: pytest.CaptureFixture[str],
) -> None:
    """15 mm sideways: the ghost's gripper sits exactly 15 mm from the real one."""
    args = ["trial", "--timeout-s", "2", "--camera-offset-mm", "15", "0", "0", "--quiet"]
    assert main(args) == 1  # a 2 s trial times out
    line = next(x for x in capsys.readouterr().out.splitlines() if x.startswith("co-location"))
    assert line.endswith(
        " px, 15.0 mm (median: the ghost's gripper from the real one in the image)"
    )

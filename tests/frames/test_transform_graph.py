"""The transform graph: covariance propagation against Monte Carlo, queries, files, the robot."""

from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest
from scipy.spatial.transform import Rotation

from arteleop.errors import ConfigurationError, FrameGraphError
from arteleop.frames import (
    EdgeKind,
    RobotFrames,
    TransformGraph,
    UncertainTransform,
    fuse,
    left_error,
    mean_transform,
)
from arteleop.robot import GRIPPER_FRAME, RIGHT_ARM_JOINTS
from arteleop.scene import RemoteSite
from arteleop.transforms import make_transform


def _random_transform(seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    return make_transform(Rotation.random(random_state=seed).as_matrix(), rng.normal(size=3))


def _random_covariance(seed: int, scale: float) -> np.ndarray:
    A = np.random.default_rng(seed).normal(size=(6, 6)) * scale
    return A @ A.T + np.eye(6) * scale**2


def _sample_covariance(samples: np.ndarray, mean: np.ndarray) -> np.ndarray:
    errors = np.array([left_error(T, mean) for T in samples])
    return errors.T @ errors / len(errors)


def _assert_covariance_close(estimate: np.ndarray, expected: np.ndarray, rtol: float) -> None:
    """Within ``rtol`` of the expected covariance's size, entry by entry."""
    assert np.abs(estimate - expected).max() < rtol * np.abs(expected).max()


def test_composition_covariance_matches_monte_carlo() -> None:
    """Left perturbations: Sigma_ac = Sigma_ab + Ad(T_ab) Sigma_bc Ad(T_ab)^T."""
    rng = np.random.default_rng(0)
    x = UncertainTransform(_random_transform(1), _random_covariance(2, 0.01))
    y = UncertainTransform(_random_transform(3), _random_covariance(4, 0.01))
    n = 40_000
    samples = x.sample(rng, n) @ y.sample(rng, n)
    composed = x @ y
    np.testing.assert_allclose(composed.T, x.T @ y.T, atol=1e-12)
    _assert_covariance_close(_sample_covariance(samples, composed.T), composed.covariance, 0.05)
    # The other convention (perturbation on the right) gives a different matrix: the test can
    # tell them apart.
    assert (
        np.abs(composed.covariance - (x.covariance + y.covariance)).max()
        > 0.2 * np.abs(composed.covariance).max()
    )


def test_inverse_covariance_matches_monte_carlo() -> None:
    rng = np.random.default_rng(5)
    x = UncertainTransform(_random_transform(6), _random_covariance(7, 0.01))
    inverse = x.inverse()
    samples = np.linalg.inv(x.sample(rng, 40_000))
    np.testing.assert_allclose(inverse.T @ x.T, np.eye(4), atol=1e-12)
    _assert_covariance_close(_sample_covariance(samples, inverse.T), inverse.covariance, 0.05)


def test_fusion_of_translations_is_the_weighted_mean() -> None:
    """For pure translations the group is the vector space: per axis, the familiar
    inverse-variance weighted mean and variance."""
    var_x, var_y = np.array([1, 4, 9, 1, 1, 1.0]) * 1e-4, np.array([4, 4, 1, 1, 1, 1.0]) * 1e-4
    x = UncertainTransform(make_transform(np.eye(3), [0.1, 0.2, 0.3]), np.diag(var_x))
    y = UncertainTransform(make_transform(np.eye(3), [0.2, 0.0, 0.5]), np.diag(var_y))
    fused = fuse(x, y)
    w = var_y[:3] / (var_x[:3] + var_y[:3])
    np.testing.assert_allclose(fused.T[:3, 3], w * [0.1, 0.2, 0.3] + (1 - w) * [0.2, 0.0, 0.5])
    np.testing.assert_allclose(np.diag(fused.covariance), var_x * var_y / (var_x + var_y))
    np.testing.assert_allclose(fused.T[:3, :3], np.eye(3), atol=1e-15)


def test_fusion_leans_towards_the_more_certain_estimate() -> None:
    x = UncertainTransform(_random_transform(8), np.eye(6) * 1e-8)
    y = UncertainTransform(_random_transform(9), np.eye(6) * 1e2)
    fused = fuse(x, y)
    assert np.linalg.norm(left_error(fused.T, x.T)) < 1e-6
    assert np.linalg.norm(left_error(fuse(y, x).T, x.T)) < 1e-6
    with pytest.raises(FrameGraphError, match="needs a covariance on both"):
        fuse(x, UncertainTransform(y.T))


def test_mean_of_symmetric_measurements_is_the_centre() -> None:
    mean = _random_transform(10)
    xi = np.random.default_rng(11).normal(size=(4, 6)) * 0.05
    measured = [(pin.exp6(s * v) * pin.SE3(mean)).homogeneous for v in xi for s in (1, -1)]
    result = mean_transform(measured)
    np.testing.assert_allclose(result.T, mean, atol=1e-12)
    expected = np.cov(np.vstack([xi, -xi]), rowvar=False) / 8
    np.testing.assert_allclose(result.covariance, expected, atol=1e-12)
    assert mean_transform(measured[:1]).covariance is None
    with pytest.raises(FrameGraphError, match="at least one measurement"):
        mean_transform([])


def _chain() -> TransformGraph:
    graph = TransformGraph()
    graph.set("world", "table", _random_transform(20), EdgeKind.FIXED)
    graph.set("table", "marker", _random_transform(21), EdgeKind.FIXED)
    graph.set("world", "base", _random_transform(22), EdgeKind.FIXED)
    graph.set("base", "camera", _random_transform(23), "calibration", np.eye(6) * 1e-6)
    graph.set("base", "gripper", _random_transform(24), EdgeKind.DYNAMIC)
    return graph


def test_queries_compose_along_the_path_forwards_and_backwards() -> None:
    g = _chain()
    T = {(e.parent, e.child): e.transform.T for e in g.edges()}
    inv = np.linalg.inv
    expected = inv(T["base", "camera"]) @ inv(T["world", "base"]) @ T["world", "table"]
    expected = expected @ T["table", "marker"]
    np.testing.assert_allclose(g.T("camera", "marker"), expected, atol=1e-12)
    np.testing.assert_allclose(g.T("marker", "camera"), inv(expected), atol=1e-12)
    assert g.path("camera", "marker") == ["camera", "base", "world", "table", "marker"]
    # The camera's covariance, carried into the marker's frame by the inverse.
    cov = g.lookup("marker", "camera").covariance
    Ad = pin.SE3(g.T("marker", "base")).action
    np.testing.assert_allclose(cov, Ad @ (np.eye(6) * 1e-6) @ Ad.T, atol=1e-15)
    np.testing.assert_allclose(g.T("base", "base"), np.eye(4))


def test_cached_queries_follow_new_values_of_every_kind_of_edge() -> None:
    g = _chain()
    before = g.T("gripper", "marker")
    assert g.lookup("gripper", "marker") is g.lookup("gripper", "marker")  # nothing changed
    g.set("base", "gripper", _random_transform(30), EdgeKind.DYNAMIC)
    moved = np.linalg.inv(_random_transform(30)) @ g.T("base", "marker")
    np.testing.assert_allclose(g.T("gripper", "marker"), moved, atol=1e-12)
    g.set("world", "table", _random_transform(31), EdgeKind.FIXED)  # inside a pre-multiplied run
    T = {(e.parent, e.child): e.transform.T for e in g.edges()}
    expected = (
        np.linalg.inv(T["base", "gripper"]) @ np.linalg.inv(T["world", "base"])
        @ T["world", "table"] @ T["table", "marker"]
    )  # fmt: skip
    after = g.T("gripper", "marker")
    np.testing.assert_allclose(after, expected, atol=1e-12)
    assert np.abs(after - before).max() > 0.1


def test_disconnected_frames_are_named_with_their_subgraphs() -> None:
    g = _chain()
    g.set("head", "kinect", _random_transform(40), EdgeKind.FIXED)
    with pytest.raises(FrameGraphError) as error:
        g.T("kinect", "marker")
    assert str(error.value) == (
        "no path from 'kinect' to 'marker': 'kinect' is connected to ['head', 'kinect'] and "
        "'marker' to ['base', 'camera', 'gripper', 'marker', 'table', 'world']; an edge between "
        "the two (a calibration, a seen marker) would connect them"
    )
    with pytest.raises(FrameGraphError, match=r"no frame 'tablet' in the graph; its frames are"):
        g.T("tablet", "base")
    g.remove("head", "kinect")
    assert "kinect" not in g.frames


def test_bad_edges_are_refused() -> None:
    g = _chain()
    with pytest.raises(FrameGraphError, match=r"edge camera -> base: the graph has it as base"):
        g.set("camera", "base", np.eye(4))
    with pytest.raises(FrameGraphError, match=r"kind 'glued' is not one of \['fixed', "):
        g.set("a", "b", np.eye(4), "glued")
    with pytest.raises(FrameGraphError, match="rotation block is not a rotation matrix"):
        g.set("a", "b", np.diag([2.0, 1, 1, 1]))
    with pytest.raises(FrameGraphError, match="positive semi-definite"):
        g.set("a", "b", np.eye(4), covariance=-np.eye(6))


def test_json_round_trip_and_dot(tmp_path: Path) -> None:
    g = _chain()
    g.save(tmp_path / "graph.json")
    loaded = TransformGraph.load(tmp_path / "graph.json")
    assert [(e.parent, e.child, e.kind) for e in loaded.edges()] == [
        (e.parent, e.child, e.kind) for e in g.edges()
    ]
    for a, b in (("camera", "marker"), ("gripper", "table")):
        np.testing.assert_allclose(loaded.T(a, b), g.T(a, b), atol=1e-13)
    np.testing.assert_array_equal(
        loaded.lookup("base", "camera").covariance, g.lookup("base", "camera").covariance
    )
    dot = g.to_dot()
    assert dot.startswith("digraph transforms {\n")
    assert '  "base" -> "camera" [label="calibration", style=dashed];' in dot.splitlines()
    assert '  "world" -> "table" [label="fixed"];' in dot.splitlines()


@pytest.mark.parametrize(
    ("edit", "message"),
    [
        (lambda e: e[1].pop("T"), r"graph.json, edge 1: needs parent, child, kind and T"),
        (lambda e: e[2].update(kind="welded"), r"edge 2 \(world -> base\): kind 'welded' is not"),
        (
            lambda e: e[3].update(T=[[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]]),
            r"edge 3 \(base -> camera\): a transform must be a finite 4x4 matrix, got shape",
        ),
    ],
)
def test_a_corrupt_graph_file_names_the_edge(tmp_path: Path, edit, message: str) -> None:
    import json

    data = json.loads(_chain().to_json())
    edit(data["edges"])
    path = tmp_path / "graph.json"
    path.write_text(json.dumps(data))
    with pytest.raises(FrameGraphError, match=message):
        TransformGraph.load(path)
    path.write_text('{"format_version": 1, "edges": [')
    with pytest.raises(FrameGraphError, match=r"graph.json: not JSON \(line 1: "):
        TransformGraph.load(path)


def test_robot_links_match_the_simulator(site: RemoteSite) -> None:
    """The URDF's joints as graph edges give the gripper where PyBullet has it."""
    rng = np.random.default_rng(50)
    limits = site.kinematics.limits(RIGHT_ARM_JOINTS)
    q = rng.uniform(limits.lower, limits.upper)
    positions = dict(zip(RIGHT_ARM_JOINTS, q.tolist(), strict=True))
    site.robot.set_joint_positions(positions)
    robot = RobotFrames(site.kinematics)
    graph = TransformGraph()
    robot.attach(graph)
    robot.update(graph, positions)
    T_pybullet = site.robot.link_transform(GRIPPER_FRAME)
    np.testing.assert_allclose(graph.T("base", GRIPPER_FRAME), T_pybullet, atol=1e-6)
    kinds = {e.kind for e in graph.edges() if e.child == "right_upper_shoulder"}
    assert kinds == {EdgeKind.DYNAMIC}
    with pytest.raises(ConfigurationError, match=r"Unknown joint 'right_s9'. Baxter's movable"):
        robot.update(graph, {"right_s9": 0.0})

import numpy as np
import pybullet as p
import pytest
import trimesh
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from scipy.integrate import quad
from scipy.spatial.transform import Rotation

from arteleop.errors import ConfigurationError
from arteleop.scene import BowlSpec, RemoteSite, bowl_collision_boxes, bowl_mesh
from arteleop.transforms import pose_to_transform, transform_points


def test_mesh_is_closed_and_matches_the_revolved_volume() -> None:
    spec = BowlSpec()
    v, f = bowl_mesh(spec, segments=256, rings=64)
    mesh = trimesh.Trimesh(v, f, process=True)
    assert mesh.is_watertight and mesh.is_winding_consistent and mesh.volume > 0
    # Pappus: volume of the shell = outer solid of revolution - inner cavity.
    t = spec.wall_thickness_m
    outer = quad(lambda h: np.pi * spec.outer_radius_m(h) ** 2, 0, spec.height_m)[0]
    inner = quad(lambda h: np.pi * (spec.outer_radius_m(h) - t) ** 2, t, spec.height_m)[0]
    assert mesh.volume == pytest.approx(outer - inner, rel=2e-3)
    np.testing.assert_allclose(mesh.bounds, [[-0.08, -0.08, 0.0], [0.08, 0.08, 0.07]], atol=1e-9)
    assert spec.center_of_mass_height_m == pytest.approx(mesh.center_mass[2], rel=2e-3)


def test_collision_boxes_tile_the_wall_up_to_the_rim() -> None:
    spec = BowlSpec()
    corners = np.array(np.meshgrid([-1, 1], [-1, 1], [-1, 1])).reshape(3, -1).T
    zs, radial = [], []
    for b in bowl_collision_boxes(spec)[:-1]:
        T = pose_to_transform(b.position_m, b.quat_wxyz)
        c = transform_points(T, corners * b.half_extents_m)
        zs.append(c[:, 2])
        # The box's centre sits mid-wall at its height.
        r = np.hypot(*b.position_m[:2])
        assert r == pytest.approx(
            spec.outer_radius_m(b.position_m[2]) - spec.wall_thickness_m / 2, abs=1e-3
        )
        radial.append(b.half_extents_m[0] * 2)
    assert min(np.min(z) for z in zs) >= 0.0
    assert max(np.max(z) for z in zs) == pytest.approx(spec.height_m, abs=2e-3)
    assert np.allclose(radial, spec.wall_thickness_m)


def test_pybullet_keeps_every_collision_piece(site: RemoteSite) -> None:
    shapes = site._client.getCollisionShapeData(site._bodies["bowl"], -1)
    assert len(shapes) == len(bowl_collision_boxes(site.config.workspace.bowl))
    lo, hi = site._client.getAABB(site._bodies["bowl"])
    assert hi[2] - lo[2] == pytest.approx(0.07, abs=0.006)  # AABBs carry a small margin
    assert site._client.getDynamicsInfo(site._bodies["bowl"], -1)[0] == pytest.approx(0.1)
    assert site._client.getCollisionShapeData(site._bodies["bowl"], -1)[0][2] == p.GEOM_MESH


def test_bowl_rests_on_the_table(site: RemoteSite) -> None:
    site.step(240)
    pos = site.observe().bowl_m
    ws = site.config.workspace
    np.testing.assert_allclose(pos[:2], ws.start_xy_m, atol=1e-3)
    assert pos[2] == pytest.approx(ws.table_top_z_m, abs=2e-3)


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"bottom_diameter_m": 0.2}, "bottom_diameter_m=0.2 exceeds diameter_m=0.16"),
        ({"height_m": -0.07}, "height_m must be > 0, got -0.07"),
        ({"wall_thickness_m": 0.05}, "leaves no cavity"),
    ],
)
def test_bad_bowl_spec(kwargs: dict, message: str) -> None:
    with pytest.raises(ConfigurationError, match=message):
        BowlSpec(**kwargs)


_FINE_VERTICES = bowl_mesh(BowlSpec(), segments=512, rings=128)[0]


@settings(max_examples=60, deadline=None)
@given(
    st.floats(-1.0, 1.0),
    st.floats(-1.0, 1.0),
    st.floats(-1.0, 1.0),
    st.floats(0.0, np.pi),
)
def test_the_lowest_point_is_the_lowest_vertex_of_the_mesh(
    x: float, y: float, z: float, angle_rad: float
) -> None:
    """Whatever the bowl's attitude, the lowest point of its wall is its mesh's lowest vertex:
    upright the bottom face, tilted the foot's edge, on its side the rim."""
    axis = np.array([x, y, z])
    assume(np.linalg.norm(axis) > 1e-3)
    spec = BowlSpec()
    T = np.eye(4)
    T[:3, :3] = Rotation.from_rotvec(angle_rad * axis / np.linalg.norm(axis)).as_matrix()
    T[:3, 3] = [0.6, -0.1, -0.2]
    assert spec.lowest_z_m(T) == pytest.approx(
        transform_points(T, _FINE_VERTICES)[:, 2].min(), abs=2e-4
    )


def test_the_lowest_point_of_a_tilted_bowl_is_its_foots_edge() -> None:
    spec = BowlSpec()
    T = np.eye(4)
    T[:3, 3] = [0.0, 0.0, 0.01]
    assert spec.lowest_z_m(T) == pytest.approx(0.01)
    tilt_rad = np.radians(10.0)
    T[:3, :3] = Rotation.from_euler("x", tilt_rad).as_matrix()
    assert spec.lowest_z_m(T) == pytest.approx(0.01 - spec.bottom_radius_m * np.sin(tilt_rad))

import importlib.metadata
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
import trimesh

from arteleop.errors import ConfigurationError, RobotDataNotFoundError
from arteleop.robot import BaxterDescription, BaxterDescriptionConfig, find_baxter_urdf
from arteleop.robot.description import HEAD_CAMERA_BLIND_LINKS


def test_urdf_is_resolved_from_the_installed_package(description: BaxterDescription) -> None:
    urdf, _share = find_baxter_urdf()
    assert urdf == description.source_urdf_path
    assert "site-packages" in str(urdf) or "dist-packages" in str(urdf)
    text = description.urdf_path.read_text()
    assert "package://" not in text
    root = ET.fromstring(text)
    for mesh in root.iter("mesh"):
        assert Path(mesh.attrib["filename"]).is_file()


def test_visual_meshes_are_decimated_and_blind_links_hidden(description: BaxterDescription) -> None:
    root = ET.parse(description.urdf_path).getroot()
    budget = BaxterDescriptionConfig().render_triangles_per_mesh
    visual_meshes = [v.find("geometry/mesh") for v in root.iter("visual")]
    files = {m.attrib["filename"] for m in visual_meshes if m is not None}
    assert files and all(f.endswith(".obj") for f in files)
    for f in files:
        assert len(trimesh.load(f, force="mesh").faces) <= budget
    for link in root.iter("link"):
        if link.attrib["name"] in HEAD_CAMERA_BLIND_LINKS:
            (visual,) = link.findall("visual")
            assert float(visual.find("geometry/sphere").attrib["radius"]) <= 1e-4
    # Collision meshes keep the original COLLADA geometry.
    collision = [c.find("geometry/mesh") for c in root.iter("collision")]
    assert all(m.attrib["filename"].endswith(".DAE") for m in collision if m is not None)


def test_missing_robot_data_is_a_clear_error(monkeypatch: pytest.MonkeyPatch) -> None:
    def missing(name: str) -> None:
        raise importlib.metadata.PackageNotFoundError(name)

    monkeypatch.setattr(importlib.metadata, "distribution", missing)
    with pytest.raises(RobotDataNotFoundError, match=r"pip install example-robot-data==6.0.0"):
        find_baxter_urdf()


def test_robot_data_without_baxter_is_a_clear_error(monkeypatch: pytest.MonkeyPatch) -> None:
    real = importlib.metadata.distribution("example-robot-data")

    class NoBaxter:
        version = real.version
        files = [f for f in real.files or () if "baxter" not in str(f)]

    monkeypatch.setattr(importlib.metadata, "distribution", lambda name: NoBaxter())
    with pytest.raises(RobotDataNotFoundError, match=r"holds no 'example-robot-data/robots/baxter"):
        find_baxter_urdf()


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"render_triangles_per_mesh": 10}, "render_triangles_per_mesh=10 is too coarse"),
        ({"finger_slot_offset_m": 0.01}, r"finger_slot_offset_m=0.01 is outside \[0, 0.0022\] m"),
    ],
)
def test_bad_description_config(kwargs: dict, message: str) -> None:
    with pytest.raises(ConfigurationError, match=message):
        BaxterDescriptionConfig(**kwargs)

"""Find Baxter's URDF in the installed example-robot-data and write the URDF arteleop loads.

example-robot-data ships no importable module: its wheel installs data under
``<prefix>/share/example-robot-data/robots/baxter_description``. We locate that folder through
the installed distribution's file list, never through a hard-coded path, and the repository holds
no copy of the robot.

The URDF we load differs from the installed one in five documented ways:

1. ``package://`` mesh paths are resolved to the installed share folder.
2. Visual meshes are replaced by decimated copies (see :mod:`arteleop.robot.render_meshes`),
   because PyBullet's CPU renderer spends its time on triangles, and links that sit fixed behind
   or below the head camera (torso, head, screen) lose their visuals: the camera never sees them
   and they only cost render time. Collision geometry, kinematics and inertias are untouched.
3. The gripper fingers sit 2 mm further in. With the URDF's finger placement the pads stop
   4.5 mm apart, so they could never pinch a thin bowl wall; the real Rethink electric gripper
   takes its fingers in several slots and the innermost one closes to about zero.
4. Each finger loses the collision box of its mounting block (5 cm wide, 10 cm above the pads).
   The two blocks overlap at every opening, so they carry no contact the simulation uses, but
   once PyBullet merges the pads into the fingers (see :func:`freeze_joints`) they would hide
   the pad gap.
5. The head loses its two collision spheres (``collision_head_link_1`` and ``_2``, 22 cm
   bubbles that Rethink's controller keeps the arms out of). Nothing in the simulation touches
   them (PyBullet checks no self-collision, and the IK keeps the arm off the table only), but
   the head camera sits 9 mm outside them: the rays of the tracker's model
   (:meth:`~arteleop.scene.RemoteSite.sight_bowl`) stopped on them over the lower third of the
   image, which the camera sees.
"""

from __future__ import annotations

import hashlib
import importlib.metadata
import xml.etree.ElementTree as ET
from collections.abc import Collection, Mapping
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pinocchio as pin
import platformdirs

from arteleop.errors import ConfigurationError, RobotDataNotFoundError
from arteleop.files import write_atomic
from arteleop.robot.render_meshes import decimated_mesh

DISTRIBUTION = "example-robot-data"
BAXTER_URDF_SUFFIX = "example-robot-data/robots/baxter_description/urdf/baxter.urdf"
PACKAGE_PREFIX = "package://"
REWRITE_VERSION = 4
"""Bump whenever :func:`_rewrite_urdf` changes, so cached URDFs from older code are not reused."""

FINGER_BLOCK_MIN_WIDTH_M = 0.03
"""A finger collision box wider than this along y is the mounting block, not the finger bar."""

# Finger joint -> sign of the origin shift that moves the finger towards the gripper's centre.
_FINGER_JOINTS = {
    "r_gripper_l_finger_joint": -1.0,
    "r_gripper_r_finger_joint": +1.0,
    "l_gripper_l_finger_joint": -1.0,
    "l_gripper_r_finger_joint": +1.0,
}


HEAD_COLLISION_SPHERES = ("collision_head_link_1", "collision_head_link_2")
"""Links whose only geometry is a collision sphere around the head: they lose it (point 5)."""

HEAD_CAMERA_BLIND_LINKS: tuple[str, ...] = (
    "torso",
    "head",
    "screen",
    "display",
    "sonar_ring",
    "collision_head_link_1",
    "collision_head_link_2",
)


@dataclass(frozen=True)
class BaxterDescriptionConfig:
    """How to build the URDF arteleop loads.

    Attributes:
        render_triangles_per_mesh: Triangle budget of each decimated visual mesh; ``None`` keeps
            the original COLLADA meshes (slow to render, about 270k triangles in all).
        finger_slot_offset_m: How far each finger is moved towards the centre, in metres.
            0.002 m leaves about 0.5 mm between the closed pads and 42 mm between the open ones
            (0 m reproduces the URDF: 4.5 mm to 46 mm).
        hidden_links: Links whose visuals are replaced by a 0.1 mm speck. The default lists the
            links fixed behind or below the head camera, which it never sees (a test checks).
        cache_dir: Where generated meshes and URDFs are kept; default: the user cache folder.
    """

    render_triangles_per_mesh: int | None = 1000
    hidden_links: tuple[str, ...] = HEAD_CAMERA_BLIND_LINKS
    finger_slot_offset_m: float = 0.002
    cache_dir: Path | None = None

    def __post_init__(self) -> None:
        if self.render_triangles_per_mesh is not None and self.render_triangles_per_mesh < 50:
            raise ConfigurationError(
                f"render_triangles_per_mesh={self.render_triangles_per_mesh} is too coarse; "
                "use at least 50, or None for the original meshes."
            )
        if not 0.0 <= self.finger_slot_offset_m <= 0.0022:
            raise ConfigurationError(
                f"finger_slot_offset_m={self.finger_slot_offset_m} is outside [0, 0.0022] m: "
                "beyond 0.0022 m the closed pads would overlap."
            )


@dataclass(frozen=True)
class BaxterDescription:
    """Paths of the robot description.

    Attributes:
        urdf_path: The URDF arteleop loads (absolute mesh paths, render meshes, finger slot).
        source_urdf_path: The URDF as installed by example-robot-data.
        share_dir: The folder that ``package://`` URIs are resolved against.
    """

    urdf_path: Path
    source_urdf_path: Path
    share_dir: Path


def find_baxter_urdf() -> tuple[Path, Path]:
    """Return (installed Baxter URDF, share folder for ``package://`` URIs).

    Raises:
        RobotDataNotFoundError: example-robot-data is missing, or has no Baxter in it.
    """
    try:
        dist = importlib.metadata.distribution(DISTRIBUTION)
    except importlib.metadata.PackageNotFoundError:
        raise RobotDataNotFoundError(
            f"The Python package '{DISTRIBUTION}' is not installed, so Baxter's URDF can't be "
            f"found. Install it with: pip install {DISTRIBUTION}==6.0.0"
        ) from None
    for file in dist.files or ():
        if file.as_posix().endswith(BAXTER_URDF_SUFFIX):
            urdf = Path(str(dist.locate_file(file)))
            if urdf.is_file():
                share = urdf.parents[4]
                return urdf, share
            raise RobotDataNotFoundError(
                f"{DISTRIBUTION} {dist.version} lists {file} but the file is missing at {urdf}. "
                f"Reinstall it: pip install --force-reinstall {DISTRIBUTION}==6.0.0"
            )
    raise RobotDataNotFoundError(
        f"{DISTRIBUTION} {dist.version} is installed but holds no '{BAXTER_URDF_SUFFIX}'. "
        f"arteleop expects {DISTRIBUTION}==6.0.0."
    )


def resolve_package_uri(uri: str, share_dir: Path) -> Path:
    """Map ``package://example-robot-data/...`` onto the installed share folder."""
    if not uri.startswith(PACKAGE_PREFIX):
        return Path(uri)
    path = share_dir / uri[len(PACKAGE_PREFIX) :]
    if not path.is_file():
        raise RobotDataNotFoundError(f"The URDF refers to {uri}, but {path} does not exist.")
    return path


def load_baxter_description(config: BaxterDescriptionConfig | None = None) -> BaxterDescription:
    """Write (or reuse from the cache) the URDF arteleop loads, and return its paths."""
    config = config or BaxterDescriptionConfig()
    source, share = find_baxter_urdf()
    version = importlib.metadata.version(DISTRIBUTION)
    cache = config.cache_dir or platformdirs.user_cache_path("arteleop")
    out_dir = cache / f"baxter-erd{version}"
    out_dir.mkdir(parents=True, exist_ok=True)

    key = hashlib.sha256(
        f"{REWRITE_VERSION}|{source}|{config.render_triangles_per_mesh}|{sorted(config.hidden_links)}|"
        f"{config.finger_slot_offset_m}".encode()
    ).hexdigest()[:16]
    urdf_path = out_dir / f"baxter-{key}.urdf"
    if not urdf_path.is_file():
        text = _rewrite_urdf(source, share, config, out_dir)
        write_atomic(urdf_path, text)
    return BaxterDescription(urdf_path=urdf_path, source_urdf_path=source, share_dir=share)


def _hide_visuals(root: ET.Element, links: Collection[str]) -> None:
    for link in root.iter("link"):
        if link.attrib.get("name") in links:
            for visual in link.findall("visual"):
                link.remove(visual)
            # PyBullet draws a link's collision shape when it has no visual: leave a speck.
            speck = ET.SubElement(ET.SubElement(link, "visual"), "geometry")
            ET.SubElement(speck, "sphere", radius="0.0001")


def hide_links(urdf_path: Path, links: Collection[str]) -> Path:
    """A copy of ``urdf_path`` (one :func:`load_baxter_description` wrote) in which the named
    links are not drawn (a 0.1 mm speck each); cached beside it."""
    key = hashlib.sha256(f"{urdf_path.name}|{sorted(links)}".encode()).hexdigest()[:16]
    out = urdf_path.with_name(f"{urdf_path.stem}-hidden-{key}.urdf")
    if not out.is_file():
        root = ET.parse(urdf_path).getroot()
        _hide_visuals(root, links)
        write_atomic(out, ET.tostring(root, encoding="unicode"))
    return out


def freeze_joints(description: BaxterDescription, positions_rad: Mapping[str, float]) -> Path:
    """A copy of ``description.urdf_path`` in which the named joints are fixed at the given
    positions (rad for revolute joints, m for prismatic ones); cached beside it.

    PyBullet's cost per step grows with every movable joint and every link: freezing the joints
    a study never moves and merging the fixed links that result cuts a step several-fold. The
    kinematics are unchanged at the frozen positions (each joint's rotation or shift is folded
    into its origin).
    """
    key = hashlib.sha256(
        f"{description.urdf_path.name}|{sorted(positions_rad.items())}".encode()
    ).hexdigest()[:16]
    out = description.urdf_path.with_name(f"{description.urdf_path.stem}-frozen-{key}.urdf")
    if out.is_file():
        return out
    root = ET.parse(description.urdf_path).getroot()
    joints = {j.attrib["name"]: j for j in root.findall("joint")}  # not transmissions' joints
    for name, q in positions_rad.items():
        joint = joints.get(name)
        if joint is None or joint.attrib["type"] not in ("revolute", "continuous", "prismatic"):
            movable = sorted(n for n, j in joints.items() if j.attrib["type"] != "fixed")
            raise ConfigurationError(
                f"Can't freeze joint '{name}': the URDF has no movable joint of that name. "
                f"Movable joints: {movable}"
            )
        origin = joint.find("origin")
        if origin is None:
            origin = ET.SubElement(joint, "origin")
        xyz = np.array([float(v) for v in origin.attrib.get("xyz", "0 0 0").split()])
        R = pin.rpy.rpyToMatrix(*(float(v) for v in origin.attrib.get("rpy", "0 0 0").split()))
        axis_el = joint.find("axis")
        axis = np.array(
            [float(v) for v in (axis_el.attrib["xyz"] if axis_el is not None else "1 0 0").split()]
        )
        axis /= np.linalg.norm(axis)
        if joint.attrib["type"] == "prismatic":
            xyz = xyz + R @ axis * q
        else:
            R = R @ pin.exp3(axis * q)
        origin.attrib["xyz"] = " ".join(f"{v:.9g}" for v in xyz)
        origin.attrib["rpy"] = " ".join(f"{v:.12g}" for v in pin.rpy.matrixToRpy(R))
        joint.attrib["type"] = "fixed"
        for tag in ("axis", "limit", "dynamics", "mimic", "safety_controller", "calibration"):
            for el in joint.findall(tag):
                joint.remove(el)
    write_atomic(out, ET.tostring(root, encoding="unicode"))
    return out


def _rewrite_urdf(source: Path, share: Path, config: BaxterDescriptionConfig, out: Path) -> str:
    root = ET.parse(source).getroot()
    _hide_visuals(root, config.hidden_links)
    for link in root.findall("link"):
        if link.attrib["name"] in HEAD_COLLISION_SPHERES:
            for collision in link.findall("collision"):
                link.remove(collision)
        if not link.attrib["name"].endswith(("_gripper_l_finger", "_gripper_r_finger")):
            continue
        for collision in link.findall("collision"):
            box = collision.find("geometry/box")
            if box is not None and float(box.attrib["size"].split()[1]) > FINGER_BLOCK_MIN_WIDTH_M:
                link.remove(collision)
    for visual in root.iter("visual"):
        mesh = visual.find("geometry/mesh")
        if mesh is None:
            continue
        path = resolve_package_uri(mesh.attrib["filename"], share)
        if config.render_triangles_per_mesh is not None:
            path = decimated_mesh(path, config.render_triangles_per_mesh, out)
        mesh.attrib["filename"] = str(path)
    for mesh in root.iter("mesh"):
        mesh.attrib["filename"] = str(resolve_package_uri(mesh.attrib["filename"], share))
    for joint in root.iter("joint"):
        sign = _FINGER_JOINTS.get(joint.attrib.get("name", ""))
        origin = joint.find("origin")
        if sign is None or origin is None:
            continue
        xyz = [float(v) for v in origin.attrib["xyz"].split()]
        xyz[1] += sign * config.finger_slot_offset_m
        origin.attrib["xyz"] = " ".join(f"{v:.6f}" for v in xyz)
    return ET.tostring(root, encoding="unicode")

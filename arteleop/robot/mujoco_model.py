"""A MuJoCo model of Baxter's right arm, built at run time from the URDF PyBullet loads.

MuJoCo cannot read the COLLADA meshes, so visuals and mesh collisions are stripped; the arm keeps
the URDF's primitive collision shapes (cylinders, boxes). Every joint but the right arm's seven is
fixed, so the model's configuration is exactly the arm's. A static box stands in for the table,
for collision avoidance.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from collections.abc import Sequence
from pathlib import Path

import mujoco

from arteleop.robot.joints import RIGHT_ARM_JOINTS

TABLE_BODY = "table"
ARM_COLLISION_BODIES: tuple[str, ...] = (
    "right_lower_forearm", "right_wrist", "right_hand_link", "right_gripper_base_link",
    "r_gripper_l_finger", "r_gripper_r_finger", "r_gripper_l_finger_tip", "r_gripper_r_finger_tip",
)  # fmt: skip
"""Bodies whose geoms must keep clear of the table: forearm, wrist, hand and gripper."""


def build_arm_model(
    urdf_path: Path,
    table_center_m: Sequence[float] | None = None,
    table_half_extents_m: Sequence[float] | None = None,
) -> mujoco.MjModel:
    """Compile the right-arm MuJoCo model, with a table box if its centre and size are given."""
    root = ET.parse(urdf_path).getroot()
    for link in root.iter("link"):
        for visual in link.findall("visual"):
            link.remove(visual)
        for collision in link.findall("collision"):
            if collision.find("geometry/mesh") is not None:
                link.remove(collision)
    for joint in root.findall("joint"):
        if joint.attrib["type"] != "fixed" and joint.attrib["name"] not in RIGHT_ARM_JOINTS:
            joint.attrib["type"] = "fixed"
    for transmission in root.findall("transmission"):
        root.remove(transmission)
    if table_center_m is not None and table_half_extents_m is not None:
        _add_table(root, table_center_m, table_half_extents_m)
    # Keep every link as a body (right_gripper would be fused away) and drop visuals.
    mj = ET.Element("mujoco")
    ET.SubElement(mj, "compiler", discardvisual="true", fusestatic="false", balanceinertia="true")
    root.insert(0, mj)
    return mujoco.MjModel.from_xml_string(ET.tostring(root, encoding="unicode"))


def body_geoms(model: mujoco.MjModel, bodies: Sequence[str]) -> list[int]:
    """Ids of the geoms attached to the named bodies."""
    ids: list[int] = []
    for name in bodies:
        b = model.body(name).id
        ids += range(model.body_geomadr[b], model.body_geomadr[b] + model.body_geomnum[b])
    return ids


def _add_table(root: ET.Element, center: Sequence[float], half: Sequence[float]) -> None:
    link = ET.SubElement(root, "link", name=TABLE_BODY)
    inertial = ET.SubElement(link, "inertial")
    ET.SubElement(inertial, "mass", value="1.0")
    ET.SubElement(inertial, "inertia", ixx="1", ixy="0", ixz="0", iyy="1", iyz="0", izz="1")
    collision = ET.SubElement(link, "collision")
    ET.SubElement(collision, "origin", xyz="0 0 0", rpy="0 0 0")
    size = " ".join(f"{2 * h:.6f}" for h in half)
    ET.SubElement(ET.SubElement(collision, "geometry"), "box", size=size)
    joint = ET.SubElement(root, "joint", name="table_fixed", type="fixed")
    ET.SubElement(joint, "parent", link="base")
    ET.SubElement(joint, "child", link=TABLE_BODY)
    ET.SubElement(joint, "origin", xyz=" ".join(f"{c:.6f}" for c in center), rpy="0 0 0")

"""The camera's drawn world mirrors the simulated one, and draws every visual of the URDF."""

import xml.etree.ElementTree as ET
from collections import Counter

import numpy as np
from pybullet_utils.bullet_client import BulletClient

from arteleop.robot import RIGHT_ARM_JOINTS
from arteleop.scene import RemoteSite
from arteleop.transforms import pose_to_transform, quat_xyzw_to_wxyz


def test_capture_copies_the_arm_and_the_bowl_into_the_drawn_world(site: RemoteSite) -> None:
    rng = np.random.default_rng(3)
    lim = site.robot.right_arm_limits
    site.robot.set_joint_positions(
        dict(zip(RIGHT_ARM_JOINTS, rng.uniform(lim.lower, lim.upper), strict=True))
    )
    site.robot.gripper.reset(0.7)
    site.place_bowl((0.6, -0.3))
    site.capture()
    drawn = site.render_world.client
    body = site.robot.body_id
    links = {drawn.getJointInfo(body, i)[12].decode(): i for i in range(drawn.getNumJoints(body))}
    for name in ("right_gripper", "r_gripper_l_finger_tip", "right_upper_forearm_visual"):
        state = drawn.getLinkState(body, links[name], computeForwardKinematics=True)
        T_drawn = pose_to_transform(state[4], quat_xyzw_to_wxyz(state[5]))
        np.testing.assert_allclose(T_drawn, site.robot.link_transform(name), atol=1e-6)
    for drawn_pose, simulated_pose in zip(
        drawn.getBasePositionAndOrientation(site._bodies["bowl"]),
        site._client.getBasePositionAndOrientation(site._bodies["bowl"]),
        strict=True,
    ):
        np.testing.assert_allclose(drawn_pose, simulated_pose)


def test_drawn_robot_has_every_visual_of_every_link(site: RemoteSite) -> None:
    root = ET.parse(site.robot.urdf_path).getroot()
    wanted = Counter(
        {link.attrib["name"]: len(link.findall("visual")) for link in root.findall("link")}
    )

    def drawn_per_link(client: BulletClient) -> Counter[str]:
        body = site.robot.body_id
        names = {
            i: client.getJointInfo(body, i)[12].decode() for i in range(client.getNumJoints(body))
        }
        return Counter(names.get(v[1], "base") for v in client.getVisualShapeData(body))

    drawn = drawn_per_link(site.render_world.client)
    assert all(drawn[name] >= n for name, n in wanted.items() if name != "base")

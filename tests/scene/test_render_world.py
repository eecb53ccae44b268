"""The camera's drawn world mirrors the simulated one, and draws every visual of the URDF."""

import xml.etree.ElementTree as ET
from collections import Counter
from collections.abc import Iterator
from dataclasses import replace
from itertools import pairwise

import numpy as np
from pybullet_utils.bullet_client import BulletClient
from scipy.ndimage import binary_erosion

from arteleop.robot import RIGHT_ARM_JOINTS
from arteleop.scene import RemoteSite, SiteConfig
from arteleop.scene.camera import render
from arteleop.scene.render_world import SceneState
from arteleop.transforms import make_transform, pose_to_transform, quat_xyzw_to_wxyz


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


def _arm_in_view(site: RemoteSite) -> Iterator[SceneState]:
    """Four states with the arm over the table, pointing down, at seeded places: an open or
    closed gripper, the left arm moved (k = 2) and the bowl lifted and tilted (k = 3)."""
    rng = np.random.default_rng(8)
    ws = site.config.workspace
    for k in range(4):
        lo, hi = ws.table_bounds_xy_m()
        above = ws.on_table(rng.uniform(lo + 0.15, hi - 0.15)) + (0.0, 0.0, 0.2)
        target = make_transform(np.diag([1.0, -1.0, -1.0]), above)
        for _ in range(8):  # PyBullet's IK improves from its own answer
            q = site.robot.pybullet_ik(target)
            site.robot.set_joint_positions(dict(zip(RIGHT_ARM_JOINTS, q, strict=True)))
        site.robot.gripper.reset(k / 3)
        state = site.scene_state()
        if k == 2:
            state.joint_positions["left_s0"] = 0.3
        if k == 3:
            lifted = np.add(state.bowl_com_position_m, (0.05, 0.1, 0.15))
            state = replace(state, bowl_com_position_m=tuple(lifted),
                            bowl_com_quat_xyzw=(0.1, 0.0, 0.0, 0.995))  # fmt: skip
        yield state


def test_the_layered_render_is_the_full_render(site_config: SiteConfig) -> None:
    """Drawing what never moves once and what moves every frame gives the full render's
    pixels exactly, for arm poses, an open or closed gripper and a bowl lifted and tilted; a
    still joint that does move (the left arm, not frozen here) redraws the still layer."""
    camera = replace(site_config.camera, renderer="tiny")
    config = replace(site_config, freeze_idle_joints=False, camera=camera)
    with RemoteSite(config) as site:
        world, request = site.render_world, site.camera.request()
        images = []
        for state in _arm_in_view(site):
            world.sync(state)
            full, layered = render(world.client, request), world.render(request)
            np.testing.assert_array_equal(layered.rgba, full.rgba)
            np.testing.assert_array_equal(layered.zbuf, full.zbuf)
            images.append(full.rgba)
        changed = [(a != b).any(axis=2).sum() for a, b in pairwise(images)]
        assert min(changed) > 1000  # each pose moved the arm across many pixels


def test_opengl_draws_what_tinyrenderer_draws(gl_site_config: SiteConfig) -> None:
    """TinyRenderer is the reference: on the same states, the OpenGL renderer hits the same
    pixels but at silhouettes, with the same depth to a micron and the same body, and the same
    colours but at edges and on the arm's white rings (TinyRenderer draws those cylinders as
    coarser hulls)."""
    camera = gl_site_config.camera
    with RemoteSite(replace(gl_site_config, freeze_idle_joints=False)) as site:
        assert site.renderer == "gl"
        world, request = site.render_world, replace(site.camera.request(), with_segmentation=True)
        for state in _arm_in_view(site):
            world.sync(state)
            tiny, gl = render(world.client, request), world.render(request)
            assert gl.segmentation is not None and tiny.segmentation is not None
            assert (gl.segmentation == 0).sum() > 50_000  # the arm is in view
            assert ((gl.zbuf < 1) == (tiny.zbuf < 1)).mean() > 0.999
            # Away from silhouettes: pixels whose 3x3 neighbourhood is one body in both images.
            same = tiny.segmentation == gl.segmentation
            inside = binary_erosion(same, np.ones((3, 3)))
            for body in np.unique(tiny.segmentation):
                body_inside = inside & binary_erosion(tiny.segmentation == body, np.ones((3, 3)))
                inside &= ~(tiny.segmentation == body) | body_inside
            hit = inside & (tiny.zbuf < 1)
            near, far = camera.near_clip_m, camera.far_clip_m
            depth_m = [far * near / (far - (far - near) * z[hit].astype(np.float64))
                       for z in (tiny.zbuf, gl.zbuf)]  # fmt: skip
            error_m = np.abs(depth_m[0] - depth_m[1])
            assert np.median(error_m) < 1e-5
            assert np.percentile(error_m, 99) < 2e-3  # the white rings' rims
            assert (tiny.rgba[inside] == gl.rgba[inside]).all(axis=1).mean() > 0.98


def test_a_body_added_to_the_drawn_world_is_drawn(site: RemoteSite) -> None:
    """The layers know only the scene's own bodies: with another (a calibration marker), the
    world renders in full."""
    from arteleop.calibration import ArucoMarker
    from arteleop.scene import MarkerBody

    world, request = site.render_world, site.camera.request()
    world.sync(site.scene_state())
    before = world.render(request)
    marker = MarkerBody(world.client, ArucoMarker(marker_id=3, side_m=0.1))
    T = np.eye(4)
    T[:3, 3] = site.config.workspace.on_table((0.7, -0.3)) + (0.0, 0.0, 0.001)
    marker.place(T)
    try:
        with_marker = world.render(request)
    finally:
        marker.remove()
    assert (with_marker.rgba != before.rgba).any(axis=2).sum() > 100
    np.testing.assert_array_equal(world.render(request).rgba, before.rgba)

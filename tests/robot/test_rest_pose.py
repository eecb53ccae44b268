import numpy as np

from arteleop.robot import GRIPPER_FRAME, REST_POSE
from arteleop.scene import RemoteSite


def test_rest_pose_is_clear_of_the_table_and_of_the_view(site: RemoteSite) -> None:
    site.step(240)  # the motors hold the pose under gravity
    np.testing.assert_allclose(site.robot.arm_positions(), REST_POSE.right, atol=0.02)
    ws = site.config.workspace
    gripper = site.robot.link_transform(GRIPPER_FRAME)[:3, 3]
    assert gripper[2] - ws.table_top_z_m > 0.15
    assert site.robot.gripper.closure() < 0.01  # open
    frame = site.capture(with_segmentation=True)
    assert (frame.segmentation == site.robot.body_id).mean() < 0.01

"""Rendering on another core gives the same frames as rendering in the loop."""

import time
from pathlib import Path

import numpy as np
import pytest

from arteleop.errors import ConfigurationError
from arteleop.robot import RIGHT_ARM_JOINTS
from arteleop.scene import RemoteSite, frame_to_point_cloud
from arteleop.scene.render_process import RenderProcess, RenderProcessError


def _wait(site: RemoteSite, timeout_s: float = 10.0):
    end = time.monotonic() + timeout_s
    while time.monotonic() < end:
        frame = site.poll_frame()
        if frame is not None:
            return frame
        time.sleep(0.002)
    raise AssertionError("no frame from the render process")


def test_frames_from_the_render_process_equal_frames_rendered_in_place(
    noiseless_site: RemoteSite,
) -> None:
    site = noiseless_site
    rng = np.random.default_rng(5)
    lim = site.robot.right_arm_limits
    for _ in range(2):
        site.robot.set_joint_positions(
            dict(zip(RIGHT_ARM_JOINTS, rng.uniform(lim.lower, lim.upper), strict=True))
        )
        site.place_bowl((0.6 + rng.uniform(-0.05, 0.05), -0.3))
        site.step(3)
        site.request_frame()
        assert site.frame_pending
        remote = _wait(site)
        assert not site.frame_pending
        here = site.capture()
        assert remote.timestamp_s == here.timestamp_s
        np.testing.assert_array_equal(remote.rgb, here.rgb)
        np.testing.assert_array_equal(remote.depth_m, here.depth_m)


def test_a_thinned_frame_is_the_full_frame_every_second_pixel_and_gives_its_cloud(
    noiseless_site: RemoteSite,
) -> None:
    site = noiseless_site
    site.step(3)
    site.request_frame(stride=2)
    thinned = _wait(site)
    full = site.capture()
    h, w = full.depth_m.shape
    assert thinned.depth_m.shape == (h // 2, w // 2)
    assert thinned.intrinsics == full.intrinsics.strided(2)
    np.testing.assert_array_equal(thinned.rgb, full.rgb[::2, ::2])
    np.testing.assert_array_equal(thinned.depth_m, full.depth_m[::2, ::2])
    # The display's cloud from either: the same points, colours and spacing.
    a, b = frame_to_point_cloud(thinned, 1), frame_to_point_cloud(full, 2)
    assert a.spacing_rad == b.spacing_rad
    np.testing.assert_array_equal(a.points_m, b.points_m)
    np.testing.assert_array_equal(a.colors, b.colors)


def test_a_thinned_frame_is_quantised_at_the_sensors_own_disparity_steps(
    site: RemoteSite,
) -> None:
    """The sensor's disparity steps are 1/8 px of the full-size image: a thinned frame's
    depths fall on them, odd eighths included (at half the focal length, only even ones)."""
    site.step(3)
    site.request_frame(stride=2)
    depth = _wait(site).depth_m
    z = depth[depth > 0].astype(np.float64)
    noise = site.config.camera.noise
    eighths = noise.baseline_m * site.camera.intrinsics.fx_px / z / noise.subpixel
    np.testing.assert_allclose(eighths, np.round(eighths), atol=1e-3)
    assert 0.3 < np.mean(np.round(eighths) % 2) < 0.7


def test_a_stride_below_one_is_refused(site: RemoteSite) -> None:
    with pytest.raises(ConfigurationError, match=r"RenderRequest.stride=0: expected a whole"):
        site.request_frame(stride=0)
    assert not site.frame_pending


def test_one_frame_at_a_time(site: RemoteSite) -> None:
    site.request_frame()
    with pytest.raises(RenderProcessError, match="still being rendered"):
        site.request_frame()
    _wait(site)


def test_a_child_that_cannot_start_says_why(site: RemoteSite, tmp_path: Path) -> None:
    missing = tmp_path / "no-such-robot.urdf"
    with pytest.raises(RenderProcessError, match=r"did not start.*no-such-robot"):
        RenderProcess(missing, site.config.workspace, site.render_world.body_ids)


def test_ctrl_c_at_the_terminal_reaches_the_parent_only(site: RemoteSite) -> None:
    """The child runs in a process group of its own: a Ctrl-C during its imports, before it
    could ignore the signal, printed its traceback; its parent stops it."""
    import os

    child = site.start_render_process()._process
    assert os.getpgid(child.pid) == child.pid != os.getpgid(0)
    site.request_frame()
    assert _wait(site) is not None


def test_closing_with_a_frame_in_flight_does_not_wait_for_it(site: RemoteSite) -> None:
    """The child may be blocked sending a full frame no one reads: it is killed, not waited
    for (Ctrl-C took 5.7 s, the wait's timeout, to stop a teleoperation)."""
    renderer = site.start_render_process()
    site.request_frame()
    start = time.monotonic()
    renderer.close()
    assert time.monotonic() - start < 3.0
    assert renderer._process.poll() is not None

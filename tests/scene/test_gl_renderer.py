"""The OpenGL head camera: the tracker's answers against TinyRenderer's, and the choice of
renderer where OpenGL is missing."""

import numpy as np
import pytest

from arteleop.errors import ConfigurationError
from arteleop.robot import RIGHT_ARM_JOINTS
from arteleop.scene import BowlTracker, HeadCameraConfig, RemoteSite, SiteConfig, gl_renderer
from arteleop.scene.camera import render
from arteleop.scene.gl_renderer import RendererUnavailableError, resolve_renderer
from arteleop.transforms import make_transform


def test_the_tracker_finds_the_bowl_alike_in_both_renderers(gl_site_config: SiteConfig) -> None:
    """Over seeded bowl places on the table, some under the arm, and one out of view: the same
    frames found, and the positions within 1 mm of each other (the frames share their depth
    noise)."""
    with RemoteSite(gl_site_config) as site:
        ws, world, camera = site.config.workspace, site.render_world, site.camera
        tracker = BowlTracker(ws.bowl)
        rng = np.random.default_rng(4)
        lo, hi = ws.table_bounds_xy_m()
        found, apart_m = [], []
        places = [rng.uniform(lo + 0.05, hi - 0.05) for _ in range(12)]
        places.append(np.array([0.40, 0.40]))  # below the bottom edge of the view
        for k, xy in enumerate(places):
            site.place_bowl((float(xy[0]), float(xy[1])))
            # Every third place, the gripper 2 cm over the rim: the arm hides much of the bowl.
            q = site.config.rest_pose.right
            if k % 3 == 0:
                above = ws.on_table(xy) + (0.0, 0.0, ws.bowl.height_m + 0.02)
                for _ in range(8):  # PyBullet's IK improves from its own answer
                    q = site.robot.pybullet_ik(make_transform(np.diag([1.0, -1.0, -1.0]), above))
                    site.robot.set_joint_positions(dict(zip(RIGHT_ARM_JOINTS, q, strict=True)))
            else:
                site.robot.set_joint_positions(dict(zip(RIGHT_ARM_JOINTS, q, strict=True)))
            world.sync(site.scene_state())
            request = camera.request()
            tracks = [
                tracker.track(camera.frame(raw, float(k)), ws.table_top_z_m)
                for raw in (render(world.client, request), world.render(request))
            ]
            found.append((tracks[0].found, tracks[1].found))
            if tracks[0].found and tracks[1].found:
                apart_m.append(np.linalg.norm(tracks[0].position_m - tracks[1].position_m))
        assert found == [(True, True)] * 12 + [(False, False)]
        assert max(apart_m) < 1e-3


def test_auto_falls_back_to_tinyrenderer_in_one_line(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    def no_context() -> None:
        raise RendererUnavailableError("no OpenGL context through EGL (OSError: libEGL.so.1)")

    monkeypatch.setattr(gl_renderer, "gl_context", no_context)
    choose = resolve_renderer.__wrapped__  # not the answer this process has cached
    assert choose("auto") == "tiny"
    assert capsys.readouterr().err == (
        "arteleop: the head camera renders with PyBullet's TinyRenderer: no OpenGL context "
        "through EGL (OSError: libEGL.so.1)\n"
    )
    with pytest.raises(RendererUnavailableError) as err:
        choose("gl")
    assert str(err.value) == (
        "The head camera can't render with OpenGL: no OpenGL context through EGL (OSError: "
        "libEGL.so.1). Or choose the renderer 'tiny' (PyBullet's TinyRenderer, several times "
        "slower)."
    )
    assert choose("tiny") == "tiny"


def test_an_unknown_renderer_is_refused() -> None:
    with pytest.raises(ConfigurationError) as err:
        HeadCameraConfig(renderer="vulkan")
    assert str(err.value) == (
        "--renderer vulkan: expected auto, gl or tiny (auto: OpenGL where an EGL context "
        "opens, PyBullet's TinyRenderer elsewhere)"
    )

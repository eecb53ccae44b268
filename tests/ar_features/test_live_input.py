"""The live input: its reset reaches the robot's target, not only the page; its steps go the
way the camera sees them; a person's presses each count."""

import socket
import time

import numpy as np
import pytest
import viser

from arteleop.ar_features.live_input import STEPS_M, LiveInput, step_directions
from arteleop.operator import HandTarget
from tests.instruments.browser import chromium, require_chromium
from tests.instruments.view_probe import CAMERA, ViewProbe, until

# One headless Chromium at a time in the suite: see tests/conftest.py.
pytestmark = pytest.mark.xdist_group("chromium")


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def test_reset_sends_the_target_back_to_rest_after_a_drag() -> None:
    """A drag sets the hand target through the gizmo's callback; "Reset" and "Start trial" put
    the gizmo back at rest from the server, which viser does not report to ``on_update``: the
    target must follow anyway (before, the robot kept aiming at the dragged pose)."""
    rest = np.array([0.6, -0.5, 0.1])
    target = HandTarget(rest)
    server = viser.ViserServer(host="127.0.0.1", port=_free_port(), verbose=False)
    try:
        live = LiveInput(server, rest, target.set)
        target.set([0.7, -0.3, 0.0], 0.8)  # what a drag and the Grip slider did
        live.reset()
        gripper_m, grip = target.get()
        np.testing.assert_array_equal(gripper_m, rest)
        assert grip == 0.0
    finally:
        server.stop()


def _looking_down_x(tilt_rad: float, yaw_rad: float = 0.0) -> np.ndarray:
    """A camera 1 m up looking along the base's x turned by ``yaw_rad`` and tilted down:
    optical frame (z forward, x right in the image, y down)."""
    c, s = np.cos(tilt_rad), np.sin(tilt_rad)
    forward = np.array([c, 0.0, -s])
    right = np.array([0.0, -1.0, 0.0])
    down = np.cross(forward, right)
    yaw = np.array([[np.cos(yaw_rad), -np.sin(yaw_rad), 0], [np.sin(yaw_rad), np.cos(yaw_rad), 0],
                    [0, 0, 1]])  # fmt: skip
    T = np.eye(4)
    T[:3, :3] = yaw @ np.column_stack([right, down, forward])
    T[:3, 3] = [0.0, 0.0, 1.0]
    return T


def _pixel(T_base_camera: np.ndarray, point_m: np.ndarray) -> np.ndarray:
    """Where a pinhole camera (unit focal length) images ``point_m``: (u right, v down)."""
    p = np.linalg.inv(T_base_camera) @ np.append(point_m, 1.0)
    return p[:2] / p[2]


def test_each_step_button_moves_the_target_that_way_in_the_cameras_image() -> None:
    """Left and right along the image's rows, away up the image and nearer down it, each on
    the table's plane; up raises the target. For cameras turned and tilted."""
    for tilt, yaw in ((0.5, 0.0), (1.0, 0.4), (0.3, -1.2)):
        T = _looking_down_x(tilt, yaw)
        steps = step_directions(T)
        point = T[:3, 3] + 1.0 * T[:3, 2]  # a point ahead of the camera
        point[2] = 0.0
        u0, v0 = _pixel(T, point)
        moved = {name: _pixel(T, point + 0.05 * d) - (u0, v0) for name, d in steps.items()}
        assert moved["left"][0] < 0 < moved["right"][0]
        assert abs(moved["left"][1]) < 1e-9  # along the row: the camera does not roll
        assert moved["away"][1] < 0 < moved["nearer"][1]
        assert moved["up"][1] < 0 < moved["down"][1]
        for name in ("left", "right", "away", "nearer"):
            assert steps[name][2] == 0.0 and np.isclose(np.linalg.norm(steps[name]), 1.0)
        np.testing.assert_array_equal(steps["up"], [0.0, 0.0, 1.0])
    # Looking straight down, away is up the image and right is right in it.
    down = step_directions(_looking_down_x(np.pi / 2, yaw_rad=0.3))
    np.testing.assert_allclose(down["away"], [np.cos(0.3), np.sin(0.3), 0.0], atol=1e-12)
    np.testing.assert_allclose(down["right"], [np.sin(0.3), -np.cos(0.3), 0.0], atol=1e-12)
    # ...and near it, either side, as straight down: no flip past the vertical.
    for past_rad in (-0.2, -0.01, 0.01, 0.2, 0.6):
        near = step_directions(_looking_down_x(np.pi / 2 + past_rad, yaw_rad=0.3))
        np.testing.assert_allclose(near["away"], down["away"], atol=1e-12)


PERSON_GAP_S = 0.1
"""Between two presses: a person's fastest repeated taps are further apart (s)."""


def _changes(grips: list[float]) -> list[float]:
    """The grips heard that differ from the one before, from the open gripper: the slider's
    number field, blurred, may send its unchanged value again."""
    return [g for before, g in zip([0.0, *grips], grips, strict=False) if g != before]


def test_a_step_the_page_does_not_offer_moves_nothing_and_prints_nothing(
    capfd: pytest.CaptureFixture[str],
) -> None:
    # A client sends what it likes: a Step of "10 m" printed a KeyError's traceback.
    rest = np.array([0.6, -0.5, 0.1])
    T = _looking_down_x(0.6)
    moves: list[np.ndarray] = []
    server = viser.ViserServer(host="127.0.0.1", port=_free_port(), verbose=False)
    try:
        LiveInput(server, rest, lambda gripper_m, grip: moves.append(gripper_m), T_base_camera=T)
        with ViewProbe(f"http://127.0.0.1:{server.get_port()}") as client:

            def control(label: str) -> object:
                ids = [m["uuid"] for m in client.sent() if m.get("props", {}).get("label") == label]
                return ids[0] if ids else None

            client.send(CAMERA)  # as a browser, first
            assert until(lambda: control("Step") and control("Move"))
            step, move = control("Step"), control("Move")
            for uuid, value in ((step, "10 m"), (move, "left"), (step, "1 cm"),
                                (move, "sideways"), (move, "right")):  # fmt: skip
                client.send({"type": "GuiUpdateMessage", "uuid": uuid, "updates": {"value": value}})
                time.sleep(0.2)  # each handled before the next: the callbacks run on a pool
            assert until(lambda: len(moves) == 1)
            time.sleep(0.3)
    finally:
        server.stop()
    (moved,) = moves
    np.testing.assert_allclose(moved, rest + STEPS_M["1 cm"] * step_directions(T)["right"])
    assert "Traceback" not in capfd.readouterr().err


def test_presses_at_a_persons_pace_each_move_the_target_once() -> None:
    """Ten presses in a real browser, alternating two buttons, a person's fastest pace apart:
    ten steps. (viser's panel sends at most one update per 50 ms, the latest: presses closer
    than that, as a script's are, merge into one.)"""
    require_chromium()
    rest = np.array([0.6, -0.5, 0.1])
    T = _looking_down_x(0.6)
    moves: list[np.ndarray] = []
    server = viser.ViserServer(host="127.0.0.1", port=_free_port(), verbose=False)
    try:
        LiveInput(server, rest, lambda gripper_m, grip: moves.append(gripper_m), T_base_camera=T)
        with chromium() as browser, browser.tab(f"http://127.0.0.1:{server.get_port()}") as tab:
            page = tab.playwright
            # Playwright's click waits for the button to take the pointer: the panel's folder
            # is still opening for a moment after the page shows it.
            buttons = [page.get_by_role("button", name=n, exact=True) for n in ("right", "up")]
            for k in range(10):
                buttons[k % 2].click()
                time.sleep(PERSON_GAP_S)
            end = time.monotonic() + 10.0
            while len(moves) < 10 and time.monotonic() < end:
                time.sleep(0.1)
    finally:
        server.stop()
    step_m = STEPS_M[next(iter(STEPS_M))]
    directions = step_directions(T)
    assert len(moves) == 10
    np.testing.assert_allclose(
        moves[-1], rest + 5 * step_m * (directions["right"] + directions["up"]), atol=1e-9
    )


def test_the_views_keys_drive_the_gripper_and_leave_the_camera_where_it_is() -> None:
    """In a real browser, D, E and the left arrow step the target right, up and left as the
    buttons do, G closes the grip, then opens it, and W steps away by the Step chosen; the
    view's camera, which those keys fly on any other page, stays put. A key held down steps
    once; in the Grip slider's number field a key is the field's."""
    require_chromium()
    rest = np.array([0.6, -0.5, 0.1])
    T = _looking_down_x(0.6)
    moves: list[np.ndarray] = []
    grips: list[float] = []

    def heard(gripper_m: np.ndarray | None, grip: float | None) -> None:
        if gripper_m is not None:
            moves.append(gripper_m)
        if grip is not None:
            grips.append(grip)

    server = viser.ViserServer(host="127.0.0.1", port=_free_port(), verbose=False)
    try:
        LiveInput(server, rest, heard, T_base_camera=T)
        with chromium() as browser, browser.tab(f"http://127.0.0.1:{server.get_port()}") as tab:
            page = tab.playwright
            page.get_by_role("button", name="nearer", exact=True).wait_for()
            (client,) = server.get_clients().values()
            camera_m = np.array(client.camera.position)
            for key in ("KeyD", "KeyE", "ArrowLeft"):
                page.keyboard.press(key)
                time.sleep(PERSON_GAP_S)
            page.keyboard.down("KeyA")  # held: the browser repeats it
            time.sleep(1.0)
            page.keyboard.up("KeyA")
            page.get_by_role("textbox").first.focus()  # the Grip slider's number field
            page.keyboard.press("KeyD")
            page.evaluate("document.activeElement.blur()")
            time.sleep(PERSON_GAP_S)
            page.keyboard.press("KeyG")
            # The panel sends its latest value at most every 50 ms: a second G before the first
            # is sent would leave only the second's. A person's next press comes after the
            # gripper has answered the first.
            end = time.monotonic() + 10.0
            while _changes(grips) != [1.0] and time.monotonic() < end:
                time.sleep(0.05)
            page.keyboard.press("KeyG")
            # The Step chosen, its closed dropdown keeps the focus: keys still step, by it.
            page.get_by_role("combobox", name="Step").click()
            page.get_by_role("option", name="1 cm", exact=True).click()
            page.keyboard.press("KeyW")
            end = time.monotonic() + 10.0
            while (len(moves) < 5 or len(_changes(grips)) < 2) and time.monotonic() < end:
                time.sleep(0.1)
            time.sleep(0.5)  # a sixth move, or the camera's flight, would show by now
            camera_after_m = np.array(client.camera.position)
    finally:
        server.stop()
    step_m, small_m = STEPS_M.values()
    directions = step_directions(T)
    assert len(moves) == 5, moves
    np.testing.assert_allclose(moves[1] - moves[0], step_m * directions["up"], atol=1e-9)
    np.testing.assert_allclose(
        moves[3], rest + step_m * (directions["up"] + directions["left"]), atol=1e-9
    )
    np.testing.assert_allclose(moves[4] - moves[3], small_m * directions["away"], atol=1e-9)
    assert _changes(grips) == [1.0, 0.0], grips
    np.testing.assert_allclose(camera_after_m, camera_m, atol=1e-6)

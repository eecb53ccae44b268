"""Live input for users without IMUs: a gizmo for the gripper's target, step buttons, a grip slider.

Each only sets a target; the loop drives the robot towards it through the same mapping, IK and
trajectory as a wearable's samples. The gizmo starts at the gripper's rest position. The step
buttons move the target as the head camera sees it (left and right in its image, away and
nearer on the table, up and down), for a person who cannot or would rather not drag; they work
from the keyboard too (:mod:`arteleop.ar_features.keys`: the view's own keys, W A S D, the
arrows, E and Q, and G for the grip; or Tab to a button and Space).
"""

from __future__ import annotations

import threading
from collections.abc import Callable

import numpy as np
import viser
from numpy.typing import ArrayLike, NDArray

from arteleop.ar_features.keys import keys_html

GIZMO_SIZE_PX = 90
"""The gizmo's size on the screen (CSS px), the same near the camera and far from it."""
STEPS_M = {"5 cm": 0.05, "1 cm": 0.01}
"""The step buttons' sizes: a reach's scale, and the bowl's placement tolerance's."""
ACROSS = ("left", "away", "nearer", "right")
HEIGHT = ("up", "down")
GIZMO, BUTTONS = "gizmo", "buttons"
"""The input devices a trial can be driven with (:meth:`LiveInput.take_devices`)."""


def step_directions(T_base_camera: ArrayLike) -> dict[str, NDArray[np.float64]]:
    """Unit directions in the base frame (z up) of each step button: away and nearer into the
    image and up it, flattened onto the table (along the line of sight for a camera looking
    ahead, up the image for one looking straight down, and turning smoothly between, and past
    straight down by up to 45 deg), left and right across it on the table (along the image's
    rows for a camera that does not roll); up and down along z. ``T_base_camera`` is the
    optical frame's pose (z forward, x right and y down in the image)."""
    R = np.asarray(T_base_camera, dtype=np.float64)[:3, :3]
    up = np.array([0.0, 0.0, 1.0])
    # The sight's and the image-up's flattened parts agree until the camera looks past straight
    # down, where the sight's turns back; their sum does not (a rule switched at the vertical
    # flipped "away" for a camera a few degrees past it).
    forward = R[:, 2] - R[:, 1]
    forward = np.append(forward[:2], 0.0) / np.linalg.norm(forward[:2])
    right = np.cross(forward, up)
    return {"left": -right, "right": right, "away": forward, "nearer": -forward, "up": up,
            "down": -up}  # fmt: skip


class LiveInput:
    """The gizmo and the slider, for every tab of ``server`` or one ``ClientHandle``'s;
    ``on_change(gripper_m, grip)`` hears every change. The slider's
    ends read open and closed, and ticks mark where the robot side closes (``close_at``) and
    opens (``open_at``) the gripper; its hint says so."""

    def __init__(
        self,
        server: viser.ViserServer | viser.ClientHandle,
        start_m: ArrayLike,
        on_change: Callable[[NDArray[np.float64] | None, float | None], None],
        close_at: float = 0.6,
        open_at: float = 0.4,
        T_base_camera: ArrayLike | None = None,
    ) -> None:
        self._start = np.asarray(start_m, dtype=np.float64)
        self._on_change = on_change
        self._used: set[str] = set()
        self._stepping = threading.Lock()
        self._gizmo = server.scene.add_transform_controls(
            "/live/gripper_target",
            # In pixels: in metres it shrank to about 20 px on a far gripper's cloud.
            scale=GIZMO_SIZE_PX,
            fixed=True,
            disable_rotations=True,
            # Over the cloud: at the gripper its own points would hide most of the handles.
            depth_test=False,
            position=self._start,
        )
        self._folder = server.gui.add_folder("Drive the robot")
        with self._folder:
            self._grip = server.gui.add_slider(
                "Grip", 0.0, 1.0, 0.05, 0.0,
                marks=((0.0, "open"), open_at, close_at, (1.0, "closed")),
                hint=f"The gripper closes when the grip reaches {close_at:g} and opens again "
                f"when it falls to {open_at:g}.",
            )  # fmt: skip
            if T_base_camera is not None:
                self._add_steps(server.gui, step_directions(T_base_camera))
            # Markdown wraps: a read-only text field cut the warning off at the panel's edge.
            self._reach = server.gui.add_markdown("")
        self._gizmo.on_update(lambda _: self._dragged())
        self._grip.on_update(lambda _: on_change(None, float(self._grip.value)))

    def _add_steps(self, gui: viser.GuiApi, directions: dict[str, NDArray[np.float64]]) -> None:
        size = gui.add_dropdown("Step", tuple(STEPS_M), hint="How far each button moves the "
                                "gripper's target.")  # fmt: skip
        for label, names in (("Move", ACROSS), ("Height", HEIGHT)):
            group = gui.add_button_group(label, names)

            def step(event: viser.GuiEvent[viser.GuiButtonGroupHandle]) -> None:
                step_m, direction = STEPS_M.get(size.value), directions.get(event.target.value)
                if step_m is None or direction is None:  # not the page's: a client's own
                    return
                delta = step_m * direction
                with self._stepping:  # clicks and drags come on a pool's threads
                    position = np.asarray(self._gizmo.position) + delta
                    self._gizmo.position = position  # set from here: on_update is not called
                    self._moved(BUTTONS, position)

            group.on_click(step)
        gui.add_html(keys_html())

    def _dragged(self) -> None:
        with self._stepping:
            self._moved(GIZMO, np.array(self._gizmo.position))

    def _moved(self, device: str, position: NDArray[np.float64]) -> None:
        self._used.add(device)
        self._on_change(position, None)

    def take_devices(self) -> str:
        """The devices that moved the target since the last call, ``+``-joined in a fixed
        order (``gizmo``, ``buttons``); empty if none did."""
        used, self._used = self._used, set()
        return "+".join(d for d in (GIZMO, BUTTONS) if d in used)

    def reset(self) -> None:
        """Back to the rest position, the grip open, no device used, and the listener told so:
        viser calls ``on_update`` only for a change made in the browser, so a target last
        dragged elsewhere would otherwise outlive the reset (the robot aimed for it, the trial
        waited for ever)."""
        with self._stepping:
            self._gizmo.position = self._start
            self._grip.value = 0.0
            self._on_change(self._start.copy(), 0.0)
            self._used.clear()

    def show(self, visible: bool) -> None:
        """Show or hide the gizmo and the panel (hidden: nothing to drag by mistake)."""
        self._gizmo.visible = visible
        self._folder.visible = visible

    def show_reach(self, reachable: bool) -> None:
        text = "" if reachable else "**Out of reach:** the arm stops at the nearest pose."
        if self._reach.content != text:
            self._reach.content = text

"""Live input for users without IMUs: a gizmo for the gripper's target and a grip slider.

Both only set a target; the loop drives the robot towards it through the same mapping, IK and
trajectory as a wearable's samples. The gizmo starts at the gripper's rest position.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import viser
from numpy.typing import ArrayLike, NDArray

GIZMO_SCALE_M = 0.15


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
    ) -> None:
        self._start = np.asarray(start_m, dtype=np.float64)
        self._on_change = on_change
        self._gizmo = server.scene.add_transform_controls(
            "/live/gripper_target",
            scale=GIZMO_SCALE_M,
            disable_rotations=True,
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
            # Markdown wraps: a read-only text field cut the warning off at the panel's edge.
            self._reach = server.gui.add_markdown("")
        self._gizmo.on_update(lambda _: on_change(np.array(self._gizmo.position), None))
        self._grip.on_update(lambda _: on_change(None, float(self._grip.value)))

    def reset(self) -> None:
        """Back to the rest position, the grip open, and the listener told so: viser calls
        ``on_update`` only for a change made in the browser, so a target last dragged elsewhere
        would otherwise outlive the reset (the robot aimed for it, the trial waited for ever)."""
        self._gizmo.position = self._start
        self._grip.value = 0.0
        self._on_change(self._start.copy(), 0.0)

    def show(self, visible: bool) -> None:
        """Show or hide the gizmo and the panel (hidden: nothing to drag by mistake)."""
        self._gizmo.visible = visible
        self._folder.visible = visible

    def show_reach(self, reachable: bool) -> None:
        text = "" if reachable else "**Out of reach:** the arm stops at the nearest pose."
        if self._reach.content != text:
            self._reach.content = text

"""The live input's reset reaches the robot's target, not only the page."""

import socket

import numpy as np
import viser

from arteleop.ar_features.live_input import LiveInput
from arteleop.operator import HandTarget


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

"""Test-only helpers: PyBullet's own tools as an independent reference; skipping a test for a
missing system package; a served study with its participant beside it."""

from __future__ import annotations

import os
import signal
import threading
from collections.abc import Callable
from typing import Any, NoReturn

import numpy as np
import pytest
from numpy.typing import NDArray

from arteleop.robot import GRIPPER_FRAME, RIGHT_ARM_JOINTS
from arteleop.scene import RemoteSite
from arteleop.transforms import make_transform

# Gripper pointing straight down (tool z = -base z), fingers opening along base y.
R_DOWN = np.diag([1.0, -1.0, -1.0])


def _down(tool_m: NDArray[np.float64]) -> NDArray[np.float64]:
    return make_transform(R_DOWN, tool_m)


def reach_down(site: RemoteSite, tool_m: NDArray[np.float64], iterations: int = 8) -> float:
    """Teleport the right arm to a top-down gripper pose at ``tool_m`` with PyBullet's IK.

    Returns the remaining position error (m) of the gripper frame, measured in the simulator.
    """
    robot = site.robot
    for _ in range(iterations):
        q = robot.pybullet_ik(_down(tool_m))
        robot.set_joint_positions(dict(zip(RIGHT_ARM_JOINTS, q, strict=True)))
    robot.command_arm(robot.arm_positions())
    return float(np.linalg.norm(robot.link_transform(GRIPPER_FRAME)[:3, 3] - tool_m))


def ik_down(site: RemoteSite, tool_m: NDArray[np.float64]) -> NDArray[np.float64]:
    """Right-arm joint targets (rad) for a top-down gripper pose, seeded from the current state."""
    return site.robot.pybullet_ik(_down(tool_m))


def unavailable(err: Exception) -> NoReturn:
    """Skip the test for a system package this machine lacks; fail it under CI, which installs
    every one (a missing one there is a broken install, not a skip)."""
    if os.environ.get("CI"):
        pytest.fail(str(err))
    pytest.skip(str(err))


def ctrl_c_reaches_it() -> None:
    """In a child process (``preexec_fn``): Ctrl-C's default action, whatever the test runner
    inherited (a runner started in the background by a shell without job control ignores
    SIGINT, and so would every child)."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def serve_to(server: Any, person: Callable[[], None]) -> None:
    """Run ``server`` (a :class:`arteleop.study.serve.StudyServer`) on this thread (its sites'
    OpenGL contexts are this thread's) while ``person`` takes part on another; the server stops
    when the person is done, and the person's failure is raised here."""
    failures: list[BaseException] = []

    def take_part() -> None:
        try:
            person()
        except BaseException as err:  # reported by the test's thread
            failures.append(err)
        finally:
            server.stop()

    thread = threading.Thread(target=take_part, daemon=True)
    thread.start()
    server.serve()
    thread.join(timeout=60)
    if failures:
        raise failures[0]

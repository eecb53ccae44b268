"""The render world in a process of its own: the head camera renders on another core.

PyBullet's TinyRenderer is single-threaded and takes 20-30 ms for a 320x240 frame of this scene,
most of a 33 ms camera period. Rendered in the loop's own thread, it leaves too little time for
the 100 Hz control and the 240 Hz physics, and a real-time run falls behind the wall clock. Here
the loop hands over the scene's state and goes on; the frame comes back when it is ready.

The child is a fresh interpreter (``python -m arteleop.scene.render_child``), talking over a
socket pair. Not ``fork``: the parent may run threads (viser's server) that a forked child would
inherit half-copied. Not multiprocessing's ``spawn`` either: it re-imports the user's main script
in the child, which re-runs any script without an ``if __name__ == "__main__"`` guard.

The child runs in a process group of its own, so Ctrl-C at the terminal reaches the parent only,
which stops the child: in the parent's group, a Ctrl-C during the child's first second (its
imports, before it could ignore the signal) printed the child's traceback.
"""

from __future__ import annotations

import socket
import subprocess
import sys
from multiprocessing.connection import Connection
from pathlib import Path

from arteleop.errors import ArteleopError
from arteleop.lifetime import Closeable
from arteleop.scene.camera import RawImage, RenderRequest
from arteleop.scene.render_world import RenderWorld, SceneState
from arteleop.scene.workspace import Workspace

START_TIMEOUT_S = 60.0


class RenderProcessError(ArteleopError):
    """The render process failed; the message carries the child's own error."""


class RenderProcess(Closeable):
    """A child process holding a :class:`RenderWorld`; one frame in flight at a time."""

    def __init__(
        self,
        robot_urdf: Path,
        ws: Workspace,
        body_ids: tuple[int, ...],
        moving_joints: tuple[str, ...] = (),
        renderer: str = "tiny",
    ) -> None:
        ours, theirs = socket.socketpair()
        self._process = subprocess.Popen(
            [sys.executable, "-m", "arteleop.scene.render_child", str(theirs.fileno())],
            pass_fds=[theirs.fileno()],
            process_group=0,
        )
        theirs.close()
        self._conn = Connection(ours.detach())
        self._busy = False
        try:
            self._conn.send((str(robot_urdf), ws, body_ids, moving_joints, renderer))
            if not self._conn.poll(START_TIMEOUT_S):
                raise RenderProcessError(
                    f"The render process did not start within {START_TIMEOUT_S:.0f} s."
                )
            started = self._conn.recv()
        except BaseException:  # Ctrl-C while it starts, too: the child must not outlive us
            self._process.kill()
            self._process.wait()
            self._conn.close()
            raise
        if isinstance(started, BaseException):
            self.close()
            raise RenderProcessError(
                f"The render process did not start with the robot URDF {robot_urdf}: {started!r}"
            ) from started

    @property
    def busy(self) -> bool:
        """A frame has been submitted and not yet collected."""
        return self._busy

    def submit(self, state: SceneState, request: RenderRequest) -> None:
        """Render ``state`` as ``request`` says; collect the result with :meth:`poll`."""
        if self._busy:
            raise RenderProcessError("A frame is still being rendered: poll() it first.")
        self._conn.send((state, request))
        self._busy = True

    def poll(self) -> RawImage | None:
        """The submitted frame if it is ready, else None (never waits)."""
        if not self._busy or not self._conn.poll():
            return None
        self._busy = False
        return self._check(self._conn.recv())

    def close(self) -> None:
        """Stop the child: told to when idle; killed with a frame in flight, which it may be
        blocked sending (a full frame is larger than the socket's buffer, and no one reads)."""
        if self._busy and self._process.poll() is None:
            self._process.kill()
            self._process.wait()
        if self._process.poll() is None:
            try:
                self._conn.send(None)
            except OSError:
                pass  # the child is already gone; waiting below is all that is left
            try:
                self._process.wait(timeout=5.0)
            except subprocess.TimeoutExpired:
                self._process.kill()
                self._process.wait()
        self._conn.close()

    @staticmethod
    def _check(message: RawImage | BaseException) -> RawImage:
        if isinstance(message, BaseException):
            raise RenderProcessError(f"The render process failed: {message!r}") from message
        return message


def serve(conn: Connection) -> None:
    """The child: build the world, then render each request until told to stop."""
    try:
        robot_urdf, ws, body_ids, moving_joints, renderer = conn.recv()
    except (EOFError, OSError):
        return  # the parent went away before it said what to build
    try:
        world = RenderWorld(Path(robot_urdf), ws, body_ids, moving_joints, renderer)
    except Exception as err:  # sent to the parent, which raises it
        try:
            conn.send(err)
        except OSError:
            pass  # the parent went away while the world was built
        return
    try:
        conn.send("ready")
        while (message := conn.recv()) is not None:
            state, request = message
            try:
                world.sync(state)
                conn.send(world.render(request))
            except Exception as err:  # sent to the parent, which raises it
                conn.send(err)
    except (EOFError, OSError):
        pass  # the parent went away without saying goodbye (a kill); nothing to render for
    finally:
        world.close()

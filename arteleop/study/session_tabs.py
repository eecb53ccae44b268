"""The browser tabs of a served study: which one controls the session, what it is shown, and
the answers its pages give. Callbacks come on viser's threads; the session waits on its own.

The first tab with the session's link controls it; another sees the robot's view and "a session
is in progress", and takes control, longest-waiting first, when the controlling tab goes. The
experimenter's link sees the robot and never controls. A page shown is shown again to any tab
that takes control later.
"""

from __future__ import annotations

import queue
import threading
from collections.abc import Callable
from typing import Any

import numpy as np
import viser
from numpy.typing import NDArray

from arteleop.ar_features import OperatorView
from arteleop.ar_features.live_input import LiveInput
from arteleop.ar_features.page_frames import frame_counter_html
from arteleop.ar_features.session_pages import SessionPages
from arteleop.errors import ArteleopError
from arteleop.operator import HandTarget
from arteleop.study.session_words import CUT_SHORT, IN_PROGRESS, OBSERVING
from arteleop.teleop import ControllerConfig


class SessionStopped(ArteleopError):
    """The server was stopped while it waited for a participant."""


class SessionTabs:
    """The tabs of ``view``'s browsers: the controlling one drives ``target`` from the gripper
    at rest ``rest_gripper_m`` (base frame, m), the camera at ``T_base_camera``; with links,
    ``observer`` is the experimenter's token."""

    def __init__(
        self,
        view: OperatorView,
        target: HandTarget,
        rest_gripper_m: NDArray[np.float64],
        T_base_camera: NDArray[np.float64],
        observer: str | None,
    ) -> None:
        self.view = view
        self._target = target
        self._rest_gripper_m, self._T_base_camera = rest_gripper_m, T_base_camera
        self._observer = observer
        self._token: str | None = None
        self._actions: queue.Queue[tuple[str, Any]] = queue.Queue()
        self._lock = threading.Lock()
        self._controller: viser.ClientHandle | None = None
        self._watching: dict[int, tuple[viser.ClientHandle, viser.GuiMarkdownHandle]] = {}
        self._pages: SessionPages | None = None
        self._live: LiveInput | None = None
        self._page: Callable[[SessionPages], None] = lambda pages: None
        self._driving = False
        self.trial_running = threading.Event()
        """A trial runs: a controlling tab that goes now interrupts it."""
        self.lost = threading.Event()
        """The controlling tab went during a trial."""
        self.stopped = threading.Event()
        """The server is stopping."""
        view.server.on_client_connect(self._connect)
        view.server.on_client_disconnect(self._disconnect)

    @property
    def controller(self) -> viser.ClientHandle | None:
        """The controlling tab's client, if any."""
        with self._lock:
            return self._controller

    @property
    def live(self) -> LiveInput | None:
        """The controlling tab's gizmo, step buttons and Grip slider, if any."""
        return self._live

    def begin_session(self, token: str | None) -> None:
        """From now on the session is the one of ``token`` (its participant's link)."""
        with self._lock:
            self._token = token

    def release(self) -> None:
        """The controlling tab keeps its page and controls nothing more (its session ended)."""
        with self._lock:
            self._controller = self._pages = self._live = None

    def show(self, page: Callable[[SessionPages], None], driving: bool = False) -> None:
        """Show ``page`` now and to any tab that takes control later, with the gizmo and the
        Grip slider if ``driving``; clicks on the pages before it are dropped (a double click
        must not answer the next page)."""
        while not self._actions.empty():
            kind, _ = self._actions.get_nowait()
            if kind == "stop":
                self._actions.put((kind, None))
                break
        with self._lock:
            self._page, self._driving = page, driving
            if self._pages is not None and self._live is not None:
                page(self._pages)
                self._live.show(driving)

    def on_pages(self, change: Callable[[SessionPages], None]) -> None:
        """Change the controlling tab's page, if there is one, not the page to show later."""
        with self._lock:
            if self._pages is not None:
                change(self._pages)

    def act(self, kind: str, value: Any = None) -> None:
        """An answer of ``kind`` from a page (or ``"stop"``)."""
        self._actions.put((kind, value))

    def stop(self) -> None:
        """End every wait: the server is stopping."""
        self.stopped.set()
        self.act("stop")

    def wait(self, kind: str) -> Any:
        """The next answer of ``kind`` (others are stale clicks: dropped); raises
        :class:`SessionStopped` once the server stops."""
        while True:
            got, value = self._actions.get()
            if got == "stop" or self.stopped.is_set():
                self.stopped.set()
                raise SessionStopped("the server was stopped")
            if got == kind:
                return value

    def _connect(self, client: viser.ClientHandle) -> None:
        with self._lock:
            if (gate := self.view.gate) is not None:
                token = gate.token_of(client.client_id)
                # The ended sessions' tabs go with this one's arrival (or the experimenter's).
                gate.expel(keep={self._token, self._observer})
                if token == self._observer:  # sees the robot, never controls
                    client.gui.add_markdown(OBSERVING)
                    return
                if token != self._token:
                    return
            if self._controller is None:
                self._take_control(client)
            else:
                self._watching[client.client_id] = (client, client.gui.add_markdown(IN_PROGRESS))

    def _disconnect(self, client: viser.ClientHandle) -> None:
        with self._lock:
            self._watching.pop(client.client_id, None)
            if self._controller is None or client.client_id != self._controller.client_id:
                return
            self._controller = self._pages = self._live = None
            if self.trial_running.is_set():
                self.lost.set()
                # Not the trial's page again: its Start belongs to the attempt that went.
                self._page = lambda p: p.message(CUT_SHORT[0], CUT_SHORT[1])
                self._driving = False
            gate = self.view.gate
            for client_id in list(self._watching):  # the longest-waiting tab of this session
                watcher, notice = self._watching.pop(client_id)
                if gate is None or gate.token_of(client_id) == self._token:
                    notice.remove()
                    self._take_control(watcher)
                    break

    def _drive(
        self, client: viser.ClientHandle, gripper_m: NDArray[np.float64] | None, grip: float | None
    ) -> None:
        """A move from ``client``'s gizmo, buttons or slider: heeded while it controls."""
        if self._controller is client:
            self._target.set(gripper_m, grip)

    def _take_control(self, client: viser.ClientHandle) -> None:
        """``client``'s tab controls the session from now on (the caller holds the lock)."""
        self._controller = client
        client.gui.add_html(frame_counter_html(client.client_id))
        self._pages = SessionPages(client.gui)
        grip = ControllerConfig().grip
        self._live = LiveInput(client, self._rest_gripper_m,
                               lambda gripper_m, grip: self._drive(client, gripper_m, grip),
                               grip.close_at, grip.open_at, self._T_base_camera)  # fmt: skip
        self._page(self._pages)
        self._live.show(self._driving)

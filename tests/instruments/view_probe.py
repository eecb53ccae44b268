"""A headless client of the operator's view: measures when updates reach a browser's socket.

It connects to the viser server the way the browser does and timestamps every binary message it
receives, so a benchmark can tell how long an update takes from :meth:`OperatorView.show_cloud`
to a connected client, and a test can check what the client got. Drawing in the browser comes on
top (one or two display frames).
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from dataclasses import dataclass

import viser
from websockets.exceptions import ConnectionClosed
from websockets.sync import client as websocket_client
from websockets.typing import Subprotocol

from arteleop.ar_features.links import LinkGate
from arteleop.lifetime import Closeable


@dataclass(frozen=True)
class Received:
    """One message: when it arrived (``time.perf_counter()`` seconds) and its bytes."""

    time_s: float
    data: bytes


class ViewProbe(Closeable):
    """Receives everything the view sends, on a thread of its own; a context manager."""

    def __init__(self, url: str, timeout_s: float = 5.0) -> None:
        ws_url = url.replace("http://", "ws://", 1)
        self._ws = websocket_client.connect(
            ws_url,
            subprotocols=[Subprotocol(f"viser-v{viser.__version__}")],
            max_size=None,
            open_timeout=timeout_s,
        )
        self.received: list[Received] = []
        self._lock = threading.Lock()
        self._thread = threading.Thread(target=self._read, daemon=True)
        self._thread.start()

    def _read(self) -> None:
        while True:
            try:
                message = self._ws.recv()
            except ConnectionClosed:
                return
            if isinstance(message, bytes):
                with self._lock:
                    self.received.append(Received(time.perf_counter(), message))

    def messages(self, min_bytes: int = 0) -> list[Received]:
        """Messages received so far, those of at least ``min_bytes`` only."""
        with self._lock:
            return [m for m in self.received if len(m.data) >= min_bytes]

    def wait_for(self, data: bytes, timeout_s: float = 5.0) -> Received | None:
        """The first message containing ``data``, waiting up to ``timeout_s``; None if none came."""
        end = time.monotonic() + timeout_s
        while time.monotonic() < end:
            for m in self.messages(len(data)):
                if data in m.data:
                    return m
            time.sleep(0.005)
        return None

    def close(self) -> None:
        self._ws.close()
        self._thread.join(timeout=5.0)


def until(done: Callable[[], object], wait_s: float = 10.0) -> bool:
    """Whether ``done()`` came true within ``wait_s``."""
    deadline = time.monotonic() + wait_s
    while not done() and time.monotonic() < deadline:
        time.sleep(0.02)
    return bool(done())


def refused(url: str, gate: LinkGate) -> bool:
    """A socket to ``url`` was closed by the gate and had been sent nothing."""
    before = gate.refused
    with ViewProbe(url) as probe:
        closed = until(lambda: gate.refused > before)
        return closed and probe.messages() == []


def admitted(url: str) -> bool:
    """A socket to ``url`` is sent the scene."""
    with ViewProbe(url) as probe:
        return until(probe.messages)

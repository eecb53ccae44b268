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

import msgspec
import viser
import zstandard
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


CAMERA = {"type": "ViewerCameraMessage", "wxyz": (1.0, 0.0, 0.0, 0.0), "position": (0.0, 0.0, 1.0),
          "fov": 1.0, "near": 0.01, "far": 100.0, "image_height": 480, "image_width": 640,
          "look_at": (0.0, 0.0, 0.0), "up_direction": (0.0, 0.0, 1.0)}  # fmt: skip
"""A browser's first message: where its camera looks; viser lists a client from then on."""


def _messages(packet: bytes) -> list[dict[str, object]]:
    """The messages in one of viser's packets: the sizes of the msgpack before and after zstd
    (8 bytes each, little-endian), the compressed msgpack, then binary buffers."""
    size, compressed = (int.from_bytes(packet[k : k + 8], "little") for k in (0, 8))
    inner = zstandard.ZstdDecompressor().decompress(packet[16 : 16 + compressed], size)
    return list(msgspec.msgpack.decode(inner)["messages"])


class ViewProbe(Closeable):
    """Receives everything the view sends, on a thread of its own; a context manager.

    ``render_reply``, if given, makes it a client the server lists (it sends a camera, as a
    browser does on connecting) that answers each frame the server asks it to draw with
    ``render_reply``, as a hostile client would (a browser answers an image's bytes)."""

    def __init__(self, url: str, timeout_s: float = 5.0, render_reply: object = None) -> None:
        ws_url = url.replace("http://", "ws://", 1)
        self._ws = websocket_client.connect(
            ws_url,
            subprotocols=[Subprotocol(f"viser-v{viser.__version__}")],
            max_size=None,
            open_timeout=timeout_s,
        )
        self.received: list[Received] = []
        self.render_replies = 0
        """Frame requests answered with ``render_reply``."""
        self._render_reply = render_reply
        self._lock = threading.Lock()
        self._thread = threading.Thread(target=self._read, daemon=True)
        self._thread.start()
        if render_reply is not None:
            self.send(CAMERA)

    def _read(self) -> None:
        while True:
            try:
                message = self._ws.recv()
            except ConnectionClosed:
                return
            if isinstance(message, bytes):
                with self._lock:
                    self.received.append(Received(time.perf_counter(), message))
                if self._render_reply is not None:
                    self._answer_renders(message)

    def _answer_renders(self, packet: bytes) -> None:
        for m in _messages(packet):
            if m.get("type") == "GetRenderRequestMessage":
                reply = {"type": "GetRenderResponseMessage", "payload": self._render_reply,
                         "render_uuid": m["render_uuid"]}  # fmt: skip
                self.render_replies += 1  # counted first: the server may act on the reply at once
                self.send(reply)

    def sent(self) -> list[dict[str, object]]:
        """Every message the server sent so far, decoded."""
        return [m for r in self.messages() for m in _messages(r.data)]

    def send(self, message: dict[str, object]) -> None:
        """Send the server one message (its ``type`` and fields), as a browser would."""
        self._ws.send(msgspec.msgpack.encode(message))

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

"""How many camera frames' clouds one browser's connection carries, measured as it goes.

The server pings the tab's socket a few times a second. A ping is written after everything
already sent to that tab and the browser answers it as it arrives, so its round trip is the
link's own plus the time the data before it waited, in the server's buffers and the network's:
beyond the least round trip seen, a queue. A tab whose queue grows is sent the cloud only every
few camera frames (the other layers, a few hundred bytes, every frame), until its queue is
short again: its picture comes less often, not later. viser already drops a tile's update that
a newer one replaces before it was sent; that alone left a slow link's kernel buffers full of
frames the browser would draw seconds late.

The rule is a delay-based congestion control's (as LEDBAT's, RFC 6817, in spirit): over
:data:`QUEUE_HIGH_S` the interval between sent frames doubles, under :data:`QUEUE_LOW_S` it
shrinks by one frame (:class:`QueueRule`).
"""

from __future__ import annotations

import asyncio
import logging
import math
import statistics
import threading
from concurrent.futures import CancelledError, Future

import viser
from websockets.asyncio.server import ServerConnection
from websockets.exceptions import ConnectionClosed

from arteleop.lifetime import Closeable

PING_EVERY_S = 0.25
"""The pause between a pong and the next ping, and between two looks at one awaited (s)."""
PING_TIMEOUT_S = 5.0
"""A ping unanswered this long is given up, and another sent (s)."""
QUEUE_HIGH_S = 0.2
"""A queue longer than this (s) halves the rate the cloud is sent at: the data a person sees
is then at least a fifth of a second older than the study's own delay."""
QUEUE_LOW_S = 0.05
"""A queue shorter than this (s) lets one more frame in each interval through."""
MAX_INTERVAL = 8
"""The cloud goes at least every this many camera frames (about 2 a second at 15 Hz)."""

_log = logging.getLogger(__name__)


def next_interval(interval: int, queue_s: float) -> int:
    """The camera frames between two clouds sent, after a ping found the tab's queue
    ``queue_s`` long (s), from ``interval``."""
    if queue_s > QUEUE_HIGH_S:
        return min(2 * interval, MAX_INTERVAL)
    if queue_s < QUEUE_LOW_S:
        return max(interval - 1, 1)
    return interval


class QueueRule:
    """The interval between clouds sent, from one tab's pings as they go.

    A ping still awaited is a queue already, and a long one on a slow link (seconds): the
    interval doubles each time the wait doubles past :data:`QUEUE_HIGH_S` beyond the least round
    trip (0 until one is answered), rather than only once the pong comes; a ping that raised it
    so is not counted again when answered.
    """

    def __init__(self, least_s: float = math.inf) -> None:
        self.interval = 1
        """Camera frames between two clouds sent (1: every frame)."""
        self.least_s = least_s
        """The least round trip answered so far (s): the link's own, without a queue."""
        self._raise_at_s = QUEUE_HIGH_S

    def sent(self) -> None:
        """A ping went."""
        self._raise_at_s = QUEUE_HIGH_S

    def waiting(self, waited_s: float) -> None:
        """The ping has waited ``waited_s`` (s) unanswered so far."""
        queue_s = waited_s - (self.least_s if math.isfinite(self.least_s) else 0.0)
        while queue_s > self._raise_at_s:
            self.interval = min(2 * self.interval, MAX_INTERVAL)
            self._raise_at_s *= 2

    def answered(self, latency_s: float) -> None:
        """Its pong came ``latency_s`` (s) after it."""
        self.least_s = min(self.least_s, latency_s)
        if self._raise_at_s == QUEUE_HIGH_S:  # not already raised for this ping's wait
            self.interval = next_interval(self.interval, latency_s - self.least_s)


class LinkPacer(Closeable):
    """Pings one tab of ``server`` (its ``client_id``) on viser's own event loop and keeps
    :attr:`interval` for its connection; a context manager. ``least_s``: the least round trip
    known of that tab from before (s). A tab already gone, or a server stopping, is paced at
    every frame and measured not at all."""

    def __init__(self, server: viser.ViserServer, client_id: int, least_s: float = math.inf):
        self.client_id = client_id
        """The tab paced."""
        self.rule = QueueRule(least_s)
        self._latencies_s: list[float] = []
        self._lock = threading.Lock()
        self._task: Future[None] | None = None
        # viser's internals, as the pinned 1.1.1 has them: the tab's socket and the loop it
        # is served from.
        websock = getattr(server, "_websock_server", None)
        connection = getattr(websock, "_live_connections", {}).get(client_id)
        loop = getattr(websock, "_background_event_loop", None)
        if connection is None or loop is None:
            return
        coroutine = self._ping(connection)
        try:
            self._task = asyncio.run_coroutine_threadsafe(coroutine, loop)
        except RuntimeError:  # the loop closed meanwhile: the server is stopping
            coroutine.close()
            return
        self._task.add_done_callback(_log_failure)

    @property
    def interval(self) -> int:
        """Camera frames between two clouds sent to this tab (1: every frame)."""
        return self.rule.interval

    async def _ping(self, connection: ServerConnection) -> None:
        loop = asyncio.get_running_loop()
        while True:
            sent_s = loop.time()
            self.rule.sent()
            # The ping itself waits while the socket's buffer is full: awaited as its pong is.
            ping = asyncio.ensure_future(connection.ping())
            pong: asyncio.Future[float] | None = None
            while pong is None or not pong.done():
                awaited = ping if pong is None else pong
                await asyncio.wait({awaited}, timeout=PING_EVERY_S)
                if pong is None and ping.done():
                    pong = ping.result()  # ConnectionClosed: the tab went
                    continue
                waited_s = loop.time() - sent_s
                self.rule.waiting(waited_s)
                if waited_s >= PING_TIMEOUT_S:
                    awaited.cancel()
                    break
            else:
                try:
                    latency_s = pong.result()
                except ConnectionClosed:
                    return
                with self._lock:
                    self._latencies_s.append(float(latency_s))
                self.rule.answered(latency_s)
            await asyncio.sleep(PING_EVERY_S)

    def take_latency_s(self) -> float | None:
        """The median round trip of the pings answered since the last call (s); None if
        none was."""
        with self._lock:
            taken, self._latencies_s = self._latencies_s, []
        return statistics.median(taken) if taken else None

    def close(self) -> None:
        if self._task is not None:
            self._task.cancel()


def _log_failure(task: Future[None]) -> None:
    """A pacer that stopped for anything but its tab going or its close says so: the tab is
    then sent every frame."""
    try:
        error = task.exception()
    except CancelledError:
        return
    if error is not None and not isinstance(error, ConnectionClosed):
        _log.warning("view: pacing a tab's stream stopped (%s); it is sent every frame", error)

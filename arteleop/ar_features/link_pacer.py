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
shrinks by one frame.
"""

from __future__ import annotations

import asyncio
import contextlib
import statistics
import threading
from concurrent.futures import Future

import viser
from websockets.exceptions import ConnectionClosed

from arteleop.lifetime import Closeable

PING_EVERY_S = 0.25
"""The pause between a pong and the next ping (s)."""
PING_TIMEOUT_S = 5.0
"""A ping unanswered this long is given up, and another sent (s)."""
QUEUE_HIGH_S = 0.2
"""A queue longer than this (s) halves the rate the cloud is sent at: the data a person sees
is then at least a fifth of a second older than the study's own delay."""
QUEUE_LOW_S = 0.05
"""A queue shorter than this (s) lets one more frame in each interval through."""
MAX_INTERVAL = 8
"""The cloud goes at least every this many camera frames (about 2 a second at 15 Hz)."""


def next_interval(interval: int, queue_s: float) -> int:
    """The camera frames between two clouds sent, after a ping found the tab's queue
    ``queue_s`` long (s), from ``interval``."""
    if queue_s > QUEUE_HIGH_S:
        return min(2 * interval, MAX_INTERVAL)
    if queue_s < QUEUE_LOW_S:
        return max(interval - 1, 1)
    return interval


class LinkPacer(Closeable):
    """Pings one tab of ``server`` (its ``client_id``) on viser's own event loop and keeps
    :attr:`interval` for its connection; a context manager. A tab already gone is paced at
    every frame and measured not at all."""

    def __init__(self, server: viser.ViserServer, client_id: int) -> None:
        self.interval = 1
        """Camera frames between two clouds sent to this tab (1: every frame)."""
        self._latencies_s: list[float] = []
        self._least_s = float("inf")
        self._lock = threading.Lock()
        self._task: Future[None] | None = None
        # viser's internals, as the pinned 1.1.1 has them: the tab's socket and the loop it
        # is served from.
        websock = getattr(server, "_websock_server", None)
        connection = getattr(websock, "_live_connections", {}).get(client_id)
        loop = getattr(websock, "_background_event_loop", None)
        if connection is not None and loop is not None and not loop.is_closed():
            self._task = asyncio.run_coroutine_threadsafe(self._ping(connection), loop)

    async def _ping(self, connection) -> None:  # type: ignore[no-untyped-def]
        loop = asyncio.get_running_loop()
        while True:
            try:
                sent_s = loop.time()
                pong = await connection.ping()
                # A pong still awaited is a queue already: each pause of waiting, as long as
                # it has been, rather than only once it comes (seconds, on a slow link).
                while not pong.done() and loop.time() - sent_s < PING_TIMEOUT_S:
                    await asyncio.wait({pong}, timeout=PING_EVERY_S)
                    if not pong.done():
                        self._judge(loop.time() - sent_s, answered=False)
                if not pong.done():
                    pong.cancel()
                    continue
                self._judge(pong.result(), answered=True)
            except ConnectionClosed:
                return
            await asyncio.sleep(PING_EVERY_S)

    def _judge(self, latency_s: float, answered: bool) -> None:
        """A ping's round trip (s), or how long an unanswered one has waited so far."""
        if answered:
            with self._lock:
                self._latencies_s.append(float(latency_s))
            self._least_s = min(self._least_s, latency_s)
        queue_s = latency_s - min(self._least_s, latency_s)
        if answered or queue_s > QUEUE_HIGH_S:
            self.interval = next_interval(self.interval, queue_s)

    def take_latency_s(self) -> float | None:
        """The median round trip of the pings answered since the last call (s); None if
        none was."""
        with self._lock:
            taken, self._latencies_s = self._latencies_s, []
        return statistics.median(taken) if taken else None

    def close(self) -> None:
        if self._task is not None:
            self._task.cancel()
            with contextlib.suppress(Exception):
                self._task.exception(timeout=1.0)

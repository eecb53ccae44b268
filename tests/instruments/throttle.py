"""A connection of limited throughput between a browser and a local server: a TCP proxy on this
machine whose server-to-browser direction carries at most a given rate, as a home connection's
downstream would (its upstream, the browser's few small messages, is not limited).

The browser opens the proxy's address in place of the server's; the page's socket then goes
through it too (viser's page opens its socket where the page came from).
"""

from __future__ import annotations

import asyncio
import threading
import time

from arteleop.lifetime import Closeable

CHUNK_BYTES = 16_384
"""What the proxy reads and forwards at a time (bytes): the bucket's burst."""


class Throttle(Closeable):
    """Forwards ``127.0.0.1:port`` to ``target_port`` on this machine, the server's bytes at
    most ``mbit_s`` megabits a second over every connection together (a token bucket one
    :data:`CHUNK_BYTES` deep); a context manager."""

    def __init__(self, target_port: int, mbit_s: float) -> None:
        self._target_port = target_port
        self._rate_bytes_s = mbit_s * 1e6 / 8
        self._tokens = float(CHUNK_BYTES)
        self._filled_s = time.monotonic()
        self.delivered: list[tuple[float, int]] = []
        """(``time.monotonic()``, bytes) of each chunk the browser was sent."""
        self._loop = asyncio.new_event_loop()
        self._thread = threading.Thread(target=self._loop.run_forever, daemon=True)
        self._thread.start()
        self._server = asyncio.run_coroutine_threadsafe(
            asyncio.start_server(self._connect, "127.0.0.1", 0), self._loop
        ).result(timeout=10)
        self.port: int = self._server.sockets[0].getsockname()[1]
        """The port the browser opens in place of the server's."""

    def mbit_s(self, from_s: float, to_s: float) -> float:
        """What the browser received between two ``time.monotonic()`` instants (Mbit/s)."""
        sent = sum(n for t, n in list(self.delivered) if from_s <= t < to_s)
        return sent * 8 / 1e6 / max(to_s - from_s, 1e-9)

    async def _connect(
        self, browser_r: asyncio.StreamReader, browser_w: asyncio.StreamWriter
    ) -> None:
        try:
            server_r, server_w = await asyncio.open_connection("127.0.0.1", self._target_port)
        except OSError:
            browser_w.close()
            return
        await asyncio.gather(self._pipe(browser_r, server_w, False),
                             self._pipe(server_r, browser_w, True))  # fmt: skip

    async def _pipe(
        self, source: asyncio.StreamReader, sink: asyncio.StreamWriter, limited: bool
    ) -> None:
        try:
            while data := await source.read(CHUNK_BYTES):
                if limited:
                    await self._take(len(data))
                    self.delivered.append((time.monotonic(), len(data)))
                sink.write(data)
                await sink.drain()
        except (ConnectionError, OSError):
            pass
        finally:
            sink.close()

    async def _take(self, n: int) -> None:
        """Wait until the bucket holds ``n`` bytes' tokens, and take them."""
        while True:
            now = time.monotonic()
            self._tokens = min(
                CHUNK_BYTES, self._tokens + (now - self._filled_s) * self._rate_bytes_s
            )
            self._filled_s = now
            if self._tokens >= n:
                self._tokens -= n
                return
            await asyncio.sleep((n - self._tokens) / self._rate_bytes_s)

    def close(self) -> None:
        self._server.close()
        self._loop.call_soon_threadsafe(self._loop.stop)
        self._thread.join(timeout=5)

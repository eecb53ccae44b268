"""Links that admit a browser to the view: a token in the address, checked before any data.

A browser that opens :func:`link_url` connects its socket to ``ws://HOST:PORT/TOKEN`` (viser's
client takes the socket's address from the page's ``websocket`` parameter). :class:`LinkGate`
looks at that path as the socket opens, before the server has sent it anything, and closes
every socket whose token is not allowed: such a browser gets the page's empty frame, never the
robot's view, a page of the study or a control.
"""

from __future__ import annotations

import threading
from collections.abc import Collection, Iterable
from typing import TYPE_CHECKING
from urllib.parse import urlsplit

from arteleop.errors import ConfigurationError

if TYPE_CHECKING:
    import viser

TOKEN_BYTES = 16
"""A token's length: 128 random bits, beyond guessing."""


def link_url(url: str, token: str) -> str:
    """The address that admits a browser with ``token`` to the view served at ``url``
    (``http://HOST:PORT``, or ``https://HOST`` behind a proxy that adds TLS: its socket is then
    ``wss://``, as a secure page may open no other)."""
    socket_url = "ws" + url.removeprefix("http")
    return f"{url}/?websocket={socket_url}/{token}"


def check_public_url(url: str) -> str:
    """``url`` if browsers can be sent to it (``http(s)://HOST[:PORT]``, nothing after; a
    trailing slash is dropped), else :class:`ConfigurationError` saying what is expected."""
    parts = urlsplit(url.strip())
    try:
        port_ok = parts.port != 0  # urlsplit refuses ports out of range or not numbers
    except ValueError:
        port_ok = False
    extra = parts.path not in ("", "/") or parts.query or parts.fragment or "@" in parts.netloc
    if parts.scheme not in ("http", "https") or not parts.hostname or not port_ok or extra:
        raise ConfigurationError(
            f"--public-url {url}: expected http://HOST[:PORT] or https://HOST[:PORT], the "
            "address participants open (a reverse proxy's or a tunnel's), with nothing after "
            "it: the proxy forwards every path, the page's and its socket's, to the server."
        )
    return f"{parts.scheme}://{parts.netloc}"  # urlsplit lowercased the scheme


class LinkGate:
    """Admits only the sockets that carry an allowed token to ``server``; none at first.

    Works on viser's socket server itself (pinned 1.1.1): its connection callbacks run as a
    socket opens, before the scene's messages are sent, where the server's public callbacks
    run only after the browser has been sent the scene.
    """

    def __init__(self, server: viser.ViserServer) -> None:
        self._sockets = server._websock_server
        self._allowed: frozenset[str] = frozenset()
        self._tokens: dict[int, str] = {}
        self._lock = threading.Lock()
        self.refused = 0
        """Sockets closed so far for want of an allowed token."""
        self._sockets.on_client_connect(self._check)
        self._sockets.on_client_disconnect(self._forget)
        self.expel()  # a socket that opened before the gate was set up

    def allow(self, tokens: Iterable[str]) -> None:
        """From now on only sockets with one of ``tokens`` open; those open stay."""
        with self._lock:
            self._allowed = frozenset(tokens)

    def token_of(self, client_id: int) -> str | None:
        """The token of an open socket (a viser client's id)."""
        with self._lock:
            return self._tokens.get(client_id)

    def count(self, token: str) -> int:
        """Open sockets admitted with ``token``."""
        with self._lock:
            return sum(t == token for t in self._tokens.values())

    def expel(self, keep: Collection[str | None] = ()) -> None:
        """Close every open socket but those admitted with a token in ``keep``."""
        loop = self._sockets._background_event_loop
        with self._lock:
            gone = [cid for cid in list(self._sockets._live_connections)
                    if self._tokens.get(cid) not in keep]  # fmt: skip
        for client_id in gone:
            if loop is not None:
                loop.call_soon_threadsafe(self._abort, client_id)

    def _check(self, client: viser.infra.WebsockClientConnection) -> None:
        """On viser's event loop, as a socket opens."""
        socket = self._sockets._live_connections[client.client_id]
        token = socket.request.path.lstrip("/") if socket.request is not None else ""
        with self._lock:
            if token in self._allowed:
                self._tokens[client.client_id] = token
                return
            self.refused += 1
        socket.transport.abort()  # nothing sent, nothing more can be

    def _forget(self, client: viser.infra.WebsockClientConnection) -> None:
        with self._lock:
            self._tokens.pop(client.client_id, None)

    def _abort(self, client_id: int) -> None:
        socket = self._sockets._live_connections.get(client_id)
        if socket is not None:
            socket.transport.abort()

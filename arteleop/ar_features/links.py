"""Links that admit a browser to the view: a token in the address, checked before any data.

A browser that opens :func:`link_url` connects its socket to ``ws://HOST:PORT/TOKEN`` (viser's
client takes the socket's address from the page's ``websocket`` parameter). :class:`LinkGate`
looks at that path as the socket opens, before the server has sent it anything, and closes
every socket whose token is not allowed: such a browser never gets the robot's view, a page of
the study or a control. The page itself is not sent to such a link either: its address says
which socket it will open, and a link without an allowed token is answered with
:data:`BAD_LINK_PAGE`, a page that says so, where viser's own would retry the socket for ever
("Connecting...") beside its developer panel.
"""

from __future__ import annotations

import gc
import http
import threading
from collections.abc import Callable, Collection, Iterable
from typing import TYPE_CHECKING, Any
from urllib.parse import parse_qs, unquote, urlsplit

from arteleop.errors import ConfigurationError

if TYPE_CHECKING:
    import viser

TOKEN_BYTES = 16
"""A token's length: 128 random bits, beyond guessing."""
BAD_LINK_PAGE = """<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>This link does not open a session</title>
<meta name="viewport" content="width=device-width, initial-scale=1">
<meta http-equiv="refresh" content="10"></head>
<body style="font-family: sans-serif; max-width: 36em; margin: 4em auto; line-height: 1.5">
<h1>This link does not open a session</h1>
<p>It may have been copied in part, or the session it opened may be over.</p>
<p>Please ask the researcher for your link.</p>
</body></html>
"""
"""What a browser is sent for a link without an allowed token (HTTP 403). It asks again every
10 s: a link opened while the server starts (its sessions' tokens not yet allowed) opens the
session once they are."""


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
        self._answer_pages(server.get_port())
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

    def admits_page(self, path: str) -> bool:
        """Whether the page at ``path`` (an HTTP request's path and query) may be sent: not
        the page (a script, a style), or the page for a socket with an allowed token."""
        parts = urlsplit(path)
        # As viser resolves a path to a file (unquoted, "." segments dropped): "/./" and
        # "/%69ndex.html" are the page too.
        segments = [
            s for s in unquote(parts.path).replace("\\", "/").split("/") if s not in ("", ".")
        ]
        if segments not in ([], ["index.html"]):
            return True
        sockets = parse_qs(parts.query).get("websocket", [])
        token = urlsplit(sockets[0]).path.lstrip("/") if sockets else ""
        with self._lock:
            return token in self._allowed

    def _answer_pages(self, port: int) -> None:
        """Answer the page's requests for links without an allowed token with
        :data:`BAD_LINK_PAGE`. viser (pinned) passes its HTTP handler to websockets' server
        and keeps no reference to it: the server is found among the objects on viser's event
        loop, by the ``port`` it listens on."""
        from websockets.asyncio.server import Server

        loop = self._sockets._background_event_loop
        (server,) = [o for o in gc.get_objects() if isinstance(o, Server) and o.loop is loop
                     and any(s.getsockname()[1] == port for s in o.sockets)]  # fmt: skip
        server.process_request = self._page_check(server.process_request)

    def _page_check(self, serve_files: Callable[..., Any] | None) -> Callable[..., Any]:
        from websockets.datastructures import Headers
        from websockets.http11 import Response

        body = BAD_LINK_PAGE.encode()
        headers = {"Content-Type": "text/html; charset=utf-8", "Cache-Control": "no-store",
                   "Content-Length": str(len(body))}  # fmt: skip

        def check(connection: Any, request: Any) -> Any:
            if request.headers.get("Upgrade") != "websocket" and not self.admits_page(request.path):
                forbidden = http.HTTPStatus.FORBIDDEN
                return Response(forbidden, forbidden.phrase, Headers(headers), body)
            return None if serve_files is None else serve_files(connection, request)

        return check

    def _forget(self, client: viser.infra.WebsockClientConnection) -> None:
        with self._lock:
            self._tokens.pop(client.client_id, None)

    def _abort(self, client_id: int) -> None:
        socket = self._sockets._live_connections.get(client_id)
        if socket is not None:
            socket.transport.abort()

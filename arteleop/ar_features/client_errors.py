"""What a browser sends that the view cannot read is that browser's doing: one line on the
console, never a traceback, and the server serves on.

viser closes the socket of a browser whose message it cannot decode (malformed bytes, a type
it does not know) and ignores an update of a property a control does not have; either way
websockets or asyncio logs the exception with its traceback, which reads as the server's own
failure. These filters turn each into one line that says what happened. A browser that goes
while the view answers it (its camera's field, fitted) makes viser warn that the answer will
never be delivered: that is nothing to say.
"""

from __future__ import annotations

import logging
import warnings

CLOSED = "view: closed a browser's connection: it sent a message the view cannot read (%s)"
IGNORED = "view: ignored a browser's update that the view cannot apply (%s)"


class _OneLine(logging.Filter):
    """Rewrites a record of a client's bad message, found by ``says`` in its message and an
    exception raised through viser's ``raised_in``, as ``line`` with the exception named,
    without the traceback."""

    def __init__(self, says: str, line: str, raised_in: str) -> None:
        super().__init__()
        self._says, self._line, self._raised_in = says, line, raised_in

    def filter(self, record: logging.LogRecord) -> bool:
        exc = record.exc_info[1] if record.exc_info else None
        if exc is not None and self._says in record.getMessage() and self._from_client(exc):
            record.msg, record.args = self._line, (f"{type(exc).__name__}: {exc}".rstrip(": "),)
            record.exc_info = record.exc_text = None
        return True

    def _from_client(self, exc: BaseException) -> bool:
        """The exception came through viser's handling of a browser's message: the server's
        own failures keep their traceback."""
        tb = exc.__traceback__
        while tb is not None:
            if tb.tb_frame.f_code.co_name == self._raised_in:
                return True
            tb = tb.tb_next
        return False


_FILTERS = {
    # websockets: the connection's handler, viser's, raised on a message it could not decode.
    "websockets.server": _OneLine("connection handler failed", CLOSED, "_message_consumer"),
    # asyncio: viser's task that applies a browser's update raised, and nothing awaited it.
    "asyncio": _OneLine("_handle_incoming_message", IGNORED, "_handle_incoming_message"),
}


def quiet_client_errors() -> None:
    """Log a browser's bad messages as one line each, from now on (once per process)."""
    for name, one_line in _FILTERS.items():
        logger = logging.getLogger(name)
        if one_line not in logger.filters:
            logger.addFilter(one_line)
    warnings.filterwarnings("ignore", "Queued a .* on a closed connection", UserWarning)

"""Resources that hold a simulator, a server or a connection: ``with`` closes them."""

from __future__ import annotations

from contextlib import AbstractContextManager
from types import TracebackType
from typing import Self


class Closeable(AbstractContextManager["Closeable"]):
    """Subclasses release what they hold in :meth:`close`; ``with`` calls it on the way out."""

    def close(self) -> None:
        raise NotImplementedError

    def __enter__(self) -> Self:
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self.close()

"""Names that moved to another module, found at their old home for a release with a warning."""

from __future__ import annotations

import importlib
import warnings
from collections.abc import Callable, Mapping
from typing import Any


def moved_names(module: str, homes: Mapping[str, str], until: str) -> Callable[[str], Any]:
    """A module ``__getattr__`` that finds each name of ``homes`` in its new home (a module's
    dotted name, or ``module:NewName`` for a name that was renamed), warning with a
    ``DeprecationWarning`` that names it, through version ``until``. The new home is imported
    only when a moved name is asked for, so an old home never depends on a new one above it."""

    def __getattr__(name: str) -> Any:
        if name not in homes:
            raise AttributeError(f"module {module!r} has no attribute {name!r}")
        home, _, new_name = homes[name].partition(":")
        renamed = f" as {new_name}" if new_name else ""
        warnings.warn(
            f"{module}.{name} has moved: import it from {home}{renamed} ({module} re-exports "
            f"it through {until} only)",
            DeprecationWarning,
            stacklevel=2,
        )
        return getattr(importlib.import_module(home), new_name or name)

    return __getattr__

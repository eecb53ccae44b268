"""Names and modules that moved, found at their old home for a release with a warning."""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.util
import sys
import warnings
from collections.abc import Callable, Mapping
from importlib.machinery import ModuleSpec
from types import ModuleType
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


class _MovedModules(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Finds each module of ``homes`` (an old dotted name, or a package's, to its new one) at
    its old name, warning; the module is the new one, imported once under its new name."""

    def __init__(self, homes: Mapping[str, str], until: str) -> None:
        self._homes = dict(homes)
        self._until = until
        self._own_specs: dict[str, ModuleSpec | None] = {}  # by old name, while being imported

    def _new_name(self, fullname: str) -> str | None:
        for old, new in self._homes.items():
            if fullname == old or fullname.startswith(old + "."):
                return new + fullname[len(old) :]
        return None

    def find_spec(self, fullname: str, path: Any, target: Any = None) -> ModuleSpec | None:
        new = self._new_name(fullname)
        if new is None or importlib.util.find_spec(new) is None:  # no such module, old or new
            return None
        warnings.warn(
            f"the module {fullname} has moved to {new}: import it from there ({fullname} is "
            f"found through {self._until} only)",
            DeprecationWarning,
            stacklevel=2,
        )
        return importlib.util.spec_from_loader(fullname, self)

    def create_module(self, spec: ModuleSpec) -> ModuleType:
        module = importlib.import_module(self._new_name(spec.name) or spec.name)
        self._own_specs[spec.name] = module.__spec__
        return module

    def exec_module(self, module: ModuleType) -> None:
        """The new module ran when it was imported under its new name; the import system has
        just given it the old name's spec, so it gets its own back (a reload runs its file)."""
        module.__spec__ = self._own_specs.pop(module.__spec__.name)


def moved_modules(homes: Mapping[str, str], until: str) -> None:
    """Let each old module name of ``homes`` (and, for a package, its modules') be imported,
    with a ``DeprecationWarning`` that names its new home, through version ``until``."""
    # First: a moved package's path would let the file finder load its modules a second time,
    # under their old names.
    sys.meta_path.insert(0, _MovedModules(homes, until))

"""Import redirection for ``python -m j5aio run --api``: ``sr.robot3`` and ``sbot`` on j5aio.

``install(api)`` puts a finder first on ``sys.meta_path`` that makes the competition's
package names resolve to j5aio's compat modules, for the program being run:

- ``--api sr-robot3``: ``sr.robot3`` (and its submodules) is
  ``j5aio.compat.sr_robot3``; ``sr`` is a namespace holding it;
- ``--api sbot``: ``sbot`` (and its submodules) is ``j5aio.compat.sbot``.

``install_hint()`` is used without ``--api``: when a program stops because it imports
``sr.robot3`` or ``sbot`` and that package is not installed, a line under the error says
which flag to add.
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.machinery
import importlib.util
import sys
import types
from collections.abc import Sequence
from typing import Final

__all__ = [
    "API_NAMES",
    "CompatFinder",
    "install",
    "install_hint",
    "missing_package_hint",
    "uninstall",
]

#: The APIs ``--api`` offers: the name given on the command line, to the names it redirects
#: (the package a program imports, to j5aio's module standing in for it).
API_NAMES: Final[dict[str, dict[str, str]]] = {
    "sr-robot3": {"sr.robot3": "j5aio.compat.sr_robot3"},
    "sbot": {"sbot": "j5aio.compat.sbot"},
}


class _AliasLoader(importlib.abc.Loader):
    """Loads a redirected name as the j5aio module it stands for (the same module object)."""

    def __init__(self, target: str) -> None:
        self._target = target

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> types.ModuleType:
        """Import the target and give it, so that both names share one module."""
        return importlib.import_module(self._target)

    def exec_module(self, module: types.ModuleType) -> None:
        """Nothing to run: the target module was run when it was imported."""


class _NamespaceLoader(importlib.abc.Loader):
    """Makes an empty package for a parent name (``sr`` of ``sr.robot3``)."""

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> types.ModuleType:
        """Make the package (a module with an empty path)."""
        module = types.ModuleType(spec.name)
        module.__path__ = []
        return module

    def exec_module(self, module: types.ModuleType) -> None:
        """Nothing to run."""


class CompatFinder(importlib.abc.MetaPathFinder):
    """Finds the redirected names of one API (see :data:`API_NAMES`).

    :param redirects: the names a program imports, to j5aio's modules standing in for them.
    """

    def __init__(self, redirects: dict[str, str]) -> None:
        self._redirects = dict(redirects)
        self._parents = {
            name.rsplit(".", 1)[0] for name in redirects if "." in name
        }

    def _target(self, fullname: str) -> str | None:
        for name, target in self._redirects.items():
            if fullname == name:
                return target
            if fullname.startswith(name + "."):
                return target + fullname[len(name):]
        return None

    def find_spec(
        self,
        fullname: str,
        path: Sequence[str] | None = None,
        target: types.ModuleType | None = None,
    ) -> importlib.machinery.ModuleSpec | None:
        """Give the spec of a redirected name, or ``None`` for every other name."""
        redirected = self._target(fullname)
        if redirected is not None:
            if importlib.util.find_spec(redirected) is None:
                return None  # (a submodule the compat module does not have)
            return importlib.machinery.ModuleSpec(fullname, _AliasLoader(redirected))
        if fullname in self._parents:
            spec = importlib.machinery.ModuleSpec(fullname, _NamespaceLoader(), is_package=True)
            spec.submodule_search_locations = []
            return spec
        return None


def missing_package_hint(error: BaseException) -> str | None:
    """The line that names ``--api`` under an uncaught import error of a competition's package.

    :returns: the hint for a ``ModuleNotFoundError`` of ``sr``, ``sr.robot3`` or ``sbot``
        (the package is not installed); ``None`` for any other error.
    """
    if not isinstance(error, ModuleNotFoundError):
        return None
    for api, redirects in API_NAMES.items():
        for name in redirects:
            if error.name in (name, name.split(".")[0]):
                return (
                    f"j5aio: {name} is not installed. To run this {api} program on j5aio, "
                    f"add --api {api}: python -m j5aio run --api {api} [options] program.py"
                )
    return None


def install(api: str) -> CompatFinder:
    """Redirect the names of ``api`` (a key of :data:`API_NAMES`) to j5aio's module.

    :returns: the finder, for :func:`uninstall`.
    :raises ValueError: ``api`` is not one of :data:`API_NAMES`.
    """
    try:
        redirects = API_NAMES[api]
    except KeyError:
        raise ValueError(
            f"unknown API {api!r}: choose one of {', '.join(API_NAMES)}"
        ) from None
    finder = CompatFinder(redirects)
    sys.meta_path.insert(0, finder)
    return finder


def install_hint() -> None:
    """Have ``run`` print :func:`missing_package_hint` under a program's uncaught error.

    The import itself fails as usual (so ``importlib.util.find_spec("sbot")`` still
    says ``None`` where sbot is not installed, and ``except ImportError`` still works).
    """
    from j5aio.tracebacks import add_hint

    add_hint(missing_package_hint)


def uninstall(finder: importlib.abc.MetaPathFinder) -> None:
    """Take ``finder`` off the meta path (if it is there)."""
    if finder in sys.meta_path:
        sys.meta_path.remove(finder)

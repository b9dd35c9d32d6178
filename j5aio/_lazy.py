"""Names a package exports but imports only when they are first used (PEP 562).

``import j5aio`` and ``import j5aio.sync`` stay light this way: a package's
``__init__`` lists what it exports and where each name lives, and the module holding a
name is imported the first time the name is looked up. That table is the package's one
list of its exports: its ``__all__`` is made from it. Type checkers see the same names
through the package's ``if TYPE_CHECKING:`` imports, each in the ``name as name`` form
that re-exports it::

    from typing import TYPE_CHECKING

    from j5aio._lazy import lazy_exports

    if TYPE_CHECKING:
        from j5aio.boards.board import Board as Board

    if not TYPE_CHECKING:
        __getattr__, __dir__ = lazy_exports(__name__, {"j5aio.boards.board": ["Board"]})

(A package may still assign its own ``__all__``; the table's is then never looked up.)

A name that is not exported but is a submodule of the package (``j5aio.vision.markers``
looked up as an attribute of ``j5aio.vision``) is imported as that submodule, as it
would be had the package imported it.
"""

from __future__ import annotations

import importlib
import sys
from collections.abc import Callable, Collection, Iterable, Mapping
from typing import Any

__all__ = ["LazyModule", "lazy_exports", "lazy_modules"]


def lazy_exports(
    package: str,
    exports: Mapping[str, Iterable[str]],
    *,
    own: Collection[str] = (),
) -> tuple[Callable[[str], Any], Callable[[], list[str]]]:
    """Return a module ``__getattr__`` and ``__dir__`` for ``package``'s lazy exports.

    The table is the one list of what the package exports: a package that does not
    assign ``__all__`` itself gets, on first look-up (a star import looks it up), the
    table's names and ``own``, sorted.

    :param package: the package's ``__name__``.
    :param exports: module name -> the names the package exports from it. A name may be
        given as ``"name:attribute"`` when the package exports the module's ``attribute``
        under another name.
    :param own: names the package defines itself that its ``__all__`` lists too.
    :raises ValueError: a name is exported from two modules.
    """
    # (Each exported name maps to its module's name, the table's own string, and only a
    # renamed one to an attribute besides: every package imported on a start builds its
    # table, so a tuple per name would be paid for on every start.)
    where: dict[str, str] = {}
    renamed: dict[str, str] = {}
    for module, names in exports.items():
        for spec in names:
            name, _, attribute = spec.partition(":")
            if name in where:
                raise ValueError(f"{package} exports {name!r} from two modules")
            where[name] = module
            if attribute:
                renamed[name] = attribute

    def __getattr__(name: str) -> Any:  # noqa: N807 - a module __getattr__ (PEP 562)
        namespace = sys.modules[package].__dict__
        module = where.get(name)
        if module is not None:
            value = getattr(importlib.import_module(module), renamed.get(name, name))
        elif name == "__all__":
            value = sorted({*where, *own})
        elif name.startswith("__"):
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        else:
            value = _submodule(package, name)
        namespace[name] = value
        return value

    def __dir__() -> list[str]:  # noqa: N807
        return sorted({*sys.modules[package].__dict__, *where})

    return __getattr__, __dir__


def _submodule(package: str, name: str) -> Any:
    full = f"{package}.{name}"
    try:
        return importlib.import_module(full)
    except ModuleNotFoundError as error:
        if error.name != full:
            raise
    raise AttributeError(f"module {package!r} has no attribute {name!r}")


class LazyModule:
    """Stands for a module until one of its attributes is used, then becomes it.

    It is bound to a global of a module (``namespace[alias]``); the first attribute
    looked up through it imports the module and rebinds that global to the real module,
    so later lookups cost nothing extra.
    """

    __slots__ = ("_alias", "_module", "_namespace")

    def __init__(self, module: str, namespace: dict[str, Any], alias: str) -> None:
        """Stand for ``module``, bound to ``namespace[alias]``."""
        self._module = module
        self._namespace = namespace
        self._alias = alias

    def __getattr__(self, attribute: str) -> Any:
        """Import the module, rebind the global to it, and look ``attribute`` up in it."""
        module = importlib.import_module(self._module)
        if self._namespace.get(self._alias) is self:
            self._namespace[self._alias] = module
        return getattr(module, attribute)

    def __repr__(self) -> str:
        return f"<lazy module {self._module!r}>"


def lazy_modules(namespace: dict[str, Any], modules: Mapping[str, str]) -> None:
    """Bind each alias of ``modules`` (alias -> module name) in ``namespace`` lazily.

    A generated module calls it with ``globals()`` for the modules its functions use
    but its definitions do not need (see :class:`LazyModule`).
    """
    for alias, module in modules.items():
        namespace[alias] = LazyModule(module, namespace, alias)

"""The generator of sync facades: typed ``__slots__`` wrappers of async boards and components.

j5aio's own facade (the package ``j5aio/sync/_generated``: one module per family of
classes, and an index of the module of each name) is made by it, and so is the sync module
of a third-party kit::

    python -m j5aio sync-gen beekit.boards -o beekit/sync.py          # write it
    python -m j5aio sync-gen beekit.boards -o beekit/sync.py --check  # CI: is it fresh?

The generator imports the given modules (a package is walked) and reads their public
classes by introspection: every board and component class defined there (a simulator or
a backend beside them is left alone). For j5aio's own facade (``CORE_SCOPE``) that is every
class of :mod:`j5aio.components` and :mod:`j5aio.boards`, plus
:class:`~j5aio.backends.environment.Environment`, :class:`~j5aio.robot.BaseRobot`, the
module-level :class:`~j5aio.backends.environment.Environment` objects of
:mod:`j5aio.backends` and the functions of :mod:`j5aio.environments`.

For each class it writes a wrapper class with ``__slots__`` that holds the core object and
follows the naming convention: a ``get_x`` / ``set_x`` coroutine pair becomes the
read-write property ``x``, a lone ``get_x`` (with no required argument) a read-only
property, every other coroutine a blocking method of the same name; plain methods,
properties and class constants are forwarded. Anything that returns a core object returns
its wrapper instead. A class of another package that already has a wrapper (a third-party
board's base, ``j5aio.boards.Board``, or its ``Motor`` components) is referred to by that
wrapper, imported from its public module (``j5aio.sync``), so a generated third-party
module imports only public names: :mod:`j5aio.sync.wrapping` and :mod:`j5aio.sync`.

A function whose signature uses a type variable bound to a wrapped class
(``get_board_group``) is typed generically in the *sync* class (pass
``beekit.sync.BeeBoard``, get a ``BoardGroup[BeeBoard]``), with one extra ``@overload``
per core class of the module being generated (pass ``j5aio.boards.sr.v4.MotorBoard``, get
a ``BoardGroup[j5aio.sync.MotorBoard]``), so that the type checker knows the exact wrapper.
The overloads are written under ``if TYPE_CHECKING:``: they are for type checkers alone,
and a module importing the facade does not make a function for each of them.

The generator is a package of small private modules, one job each: ``_scope`` (what to
wrap), ``_discovery`` (finding it), ``_namespace`` (resolving annotations), ``_renderer``
(annotations as source), ``_members`` (kinds of members), ``_class_writer`` (one wrapper
class), ``_module_writer`` (the whole module) and ``_cli`` (the command line). Importing
this package loads none of them until a name is used, so the command line of j5aio pays
for the generator only when ``sync-gen`` runs.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from j5aio.syncgen._cli import (
        add_arguments,
        check_or_write,
        check_or_write_package,
        main,
        run,
    )
    from j5aio.syncgen._discovery import Discovery, discover, existing_wrappers
    from j5aio.syncgen._module_writer import generate, generate_core, render_core, render_module
    from j5aio.syncgen._scope import CORE_OUTPUT, CORE_PACKAGE, CORE_SCOPE, Scope, core_family

__all__ = [
    "CORE_OUTPUT",
    "CORE_PACKAGE",
    "CORE_SCOPE",
    "Discovery",
    "Scope",
    "add_arguments",
    "check_or_write",
    "check_or_write_package",
    "core_family",
    "discover",
    "existing_wrappers",
    "generate",
    "generate_core",
    "main",
    "render_core",
    "render_module",
    "run",
]

#: The module of each public name.
_HOMES = {
    "CORE_OUTPUT": "_scope",
    "CORE_PACKAGE": "_scope",
    "CORE_SCOPE": "_scope",
    "Scope": "_scope",
    "core_family": "_scope",
    "Discovery": "_discovery",
    "discover": "_discovery",
    "existing_wrappers": "_discovery",
    "generate": "_module_writer",
    "generate_core": "_module_writer",
    "render_core": "_module_writer",
    "render_module": "_module_writer",
    "add_arguments": "_cli",
    "check_or_write": "_cli",
    "check_or_write_package": "_cli",
    "main": "_cli",
    "run": "_cli",
}

if not TYPE_CHECKING:  # the names are imported above for type checkers

    def __getattr__(name: str) -> Any:
        """Load the module of ``name`` on first use (PEP 562)."""
        home = _HOMES.get(name)
        if home is None:
            raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
        import importlib

        value = getattr(importlib.import_module(f"{__name__}.{home}"), name)
        globals()[name] = value
        return value

    def __dir__() -> list[str]:
        """The names of the package, with those loaded on first use."""
        return sorted({*globals(), *__all__})

"""Finding what to wrap: the board and component classes, environments and functions of a scope."""

from __future__ import annotations

import enum
import importlib
import inspect
import pkgutil
import sys
import types
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from typing import Any

from j5aio.syncgen._scope import CORE_SCOPE, Scope

__all__ = ["Discovery", "discover", "existing_wrappers"]

# --------------------------------------------------------------------------- discovery


@dataclass
class Discovery:
    """What the generator wraps: core classes (bases first) and environment objects."""

    classes: list[type] = field(default_factory=list)
    environments: dict[str, tuple[str, str]] = field(default_factory=dict)
    """Exported name -> (module, attribute) of each environment object."""
    functions: list[Callable[..., Any]] = field(default_factory=list)
    """Module-level functions that take or return wrapped objects."""
    scope: Scope = CORE_SCOPE
    """What was searched."""


def _walk(package_name: str, skipped: tuple[str, ...]) -> list[types.ModuleType]:
    package = importlib.import_module(package_name)
    modules = [package]
    for info in pkgutil.walk_packages(getattr(package, "__path__", []), package_name + "."):
        if skipped and info.name.startswith(skipped):
            continue
        modules.append(importlib.import_module(info.name))
    return modules


def _is_wrappable(cls: type) -> bool:
    from j5aio.backends.backend import Backend
    from j5aio.components.component import Interface
    return not (
        issubclass(cls, enum.Enum | Interface | BaseException | Backend)
        or cls.__name__.startswith("_")
        or any(  # a sync wrapper; compared by name, so that j5aio.sync is not imported
            (k.__module__, k.__qualname__) == ("j5aio.sync.wrapping", "SyncWrapper")
            for k in cls.__mro__
        )
    )


def discover(scope: Scope = CORE_SCOPE) -> Discovery:
    """Find the classes (and, for j5aio's facade, environments and functions) of ``scope``.

    :raises ImportError: a module of the scope cannot be imported.
    """
    from j5aio.backends.environment import Environment
    from j5aio.boards.board import Board
    from j5aio.components.component import Component

    found: dict[type, None] = {}
    for package in scope.modules:
        for module in _walk(package, scope.skipped_packages):
            for obj in vars(module).values():
                if (
                    inspect.isclass(obj)
                    and obj.__module__ == module.__name__
                    and _is_wrappable(obj)
                    and (scope.is_core or issubclass(obj, Board | Component))
                ):
                    found[obj] = None
    for module_name, class_name in scope.extra_classes:
        found[getattr(importlib.import_module(module_name), class_name)] = None
    discovery = Discovery(classes=_bases_first(found), scope=scope)

    seen: dict[int, str] = {}
    for package in scope.environment_packages:
        for module in _walk(package, scope.skipped_packages):
            for name, obj in sorted(vars(module).items()):
                if (
                    isinstance(obj, Environment)
                    and not name.startswith("_")
                    and id(obj) not in seen
                ):
                    if name in discovery.environments:
                        raise RuntimeError(f"two environments are both called {name}")
                    seen[id(obj)] = name
                    discovery.environments[name] = (module.__name__, name)
    for module_name in scope.function_modules:
        module = importlib.import_module(module_name)
        for name, obj in vars(module).items():
            if (
                inspect.isfunction(obj)
                and obj.__module__ == module_name
                and not name.startswith("_")
            ):
                discovery.functions.append(obj)
    return discovery


def _bases_first(classes: Iterable[type]) -> list[type]:
    ordered: list[type] = []
    pending = sorted(classes, key=lambda c: (len(c.__mro__), c.__module__, c.__qualname__))
    placed: set[type] = set()
    while pending:
        for cls in pending:
            if all(base in placed or base not in pending for base in cls.__mro__[1:]):
                ordered.append(cls)
                placed.add(cls)
                pending.remove(cls)
                break
    return ordered


def _public_module(obj: Any) -> str:
    """The module to import ``obj`` from: its own, or the nearest public package exporting it."""
    module: str = obj.__module__
    parts = module.split(".")
    if not any(part.startswith("_") for part in parts):
        return module
    for end in range(len(parts) - 1, 0, -1):
        candidate = ".".join(parts[:end])
        if any(part.startswith("_") for part in parts[:end]):
            continue
        if getattr(sys.modules.get(candidate), obj.__qualname__, None) is obj:
            return candidate
    return module


def existing_wrappers(skip: Iterable[type] = ()) -> dict[type, tuple[str, str]]:
    """Return core class -> (public module, name) of every wrapper registered so far.

    Importing ``j5aio.sync._generated`` tells where j5aio's own are (all are imported
    here); a kit's generated module registers its own when imported. ``skip`` leaves out
    the classes about to be generated afresh.
    """
    import j5aio.sync._generated  # noqa: F401 - registers j5aio's own wrappers
    from j5aio.sync.wrapping import registered

    skipped = set(skip)
    return {
        core: (_public_module(wrapper), wrapper.__qualname__)
        for core, wrapper in registered().items()
        if core not in skipped
    }

"""The registry of board kinds, public as :mod:`j5aio.board_kinds` (documented there).

It lives among the backends because the backends' environments and identification read
it, and it imports none of them: a kind names its backends and simulators by import path
(:mod:`j5aio.import_paths`), imported the first time they are read. It imports the
boards (j5aio's own kinds name their board classes) and the Backend base class only.
"""

from __future__ import annotations

import warnings
from collections.abc import Iterable, Mapping
from dataclasses import replace
from types import MappingProxyType
from typing import Final

from j5aio import _entry_points
from j5aio.backends import _kind_types
from j5aio.backends._kind_types import (
    _BACKEND_ROLES,
    DEFAULT_KIT,
    BackendField,
    BoardField,
    BoardKind,
    KitDefinition,
    SimulatorClass,
    SimulatorEntry,
)

__all__ = [
    "DEFAULT_KIT",
    "ENTRY_POINT_GROUP",
    "BackendField",
    "BoardField",
    "BoardKind",
    "BoardPluginWarning",
    "KitDefinition",
    "SimulatorClass",
    "SimulatorEntry",
    "SimulatorFactory",
    "SimulatorTransport",
    "board_kinds",
    "find_simulator",
    "get_kit",
    "kits",
    "register",
    "simulator_entries",
    "unregister",
]

SimulatorFactory = _kind_types.SimulatorFactory
SimulatorTransport = _kind_types.SimulatorTransport

#: The entry point group through which other packages register board kinds and kits.
ENTRY_POINT_GROUP: Final = "j5aio.boards"

class BoardPluginWarning(UserWarning):
    """A plugin's entry in the ``j5aio.boards`` entry point group was left out."""


class _Registry:
    """The kinds and kits known so far; plugins are loaded on first use."""

    def __init__(self) -> None:
        self._kinds: dict[str, BoardKind] = {}
        self._kits: dict[str, KitDefinition] = {}
        self._loaded = False
        self._loading = False

    def _ensure_loaded(self) -> None:
        if self._loaded:
            return
        if self._loading:
            raise RuntimeError(
                "the board kinds were read while they were being loaded: a module that "
                "registers board kinds must not read them when it is imported"
            )
        self._loading = True
        try:
            from j5aio.backends import _builtin_kinds  # (the boards' modules, on first use)

            for item in _builtin_kinds.entries():
                self._add(item)
            self._load_plugins()
            self._loaded = True
        finally:
            self._loading = False

    def _load_plugins(self) -> None:
        for entry_point in _entry_points.find(ENTRY_POINT_GROUP):
            package = entry_point.package
            try:
                loaded = entry_point.load()
                items = _flatten(loaded() if callable(loaded) and not _is_entry(loaded) else loaded)
                prepared = [_with_package(item, package) for item in items]
                for item in prepared:
                    self._check_new(item)
            except Exception as error:  # a broken plugin must not break j5aio
                warnings.warn(
                    f"j5aio: left out the board plugin {entry_point.name!r} "
                    f"({entry_point.value}) of package {package!r}: "
                    f"{type(error).__name__}: {error}",
                    BoardPluginWarning,
                    stacklevel=2,
                )
                continue
            for item in prepared:
                self._add(item)

    def _check_new(self, item: BoardKind | KitDefinition) -> None:
        if isinstance(item, KitDefinition):
            if item.name in self._kits:
                raise ValueError(f"a kit called {item.name!r} is already registered")
            return
        if item.name in self._kinds:
            raise ValueError(f"a board kind called {item.name!r} is already registered")
        taken = {entry.name for kind in self._kinds.values() for entry in kind.simulators}
        for entry in item.simulators:
            if entry.name in taken:
                raise ValueError(f"a simulator called {entry.name!r} is already registered")

    def _add(self, item: BoardKind | KitDefinition) -> None:
        self._check_new(item)
        if isinstance(item, KitDefinition):
            self._kits[item.name] = item
        else:
            self._kinds[item.name] = item

    def add(self, item: BoardKind | KitDefinition) -> None:
        self._ensure_loaded()
        self._add(item)

    def remove(self, name: str) -> None:
        self._ensure_loaded()
        if name in self._kinds:
            del self._kinds[name]
        elif name in self._kits:
            del self._kits[name]
        else:
            raise KeyError(f"no board kind or kit called {name!r} is registered")

    def kinds(self) -> tuple[BoardKind, ...]:
        self._ensure_loaded()
        return tuple(self._kinds.values())

    def kits(self) -> dict[str, KitDefinition]:
        self._ensure_loaded()
        result = dict(self._kits)
        # Simulators that join kits (a plugin's board in j5aio's kits, say).
        for kind in self._kinds.values():
            for entry in kind.simulators:
                for kit_name, count in entry.kits.items():
                    kit = result.get(kit_name)
                    if kit is None or entry.name in kit.boards:
                        continue
                    result[kit_name] = replace(kit, boards={**kit.boards, entry.name: count})
        return result


def _is_entry(obj: object) -> bool:
    return isinstance(obj, BoardKind | KitDefinition | type)


def _flatten(obj: object) -> list[BoardKind | KitDefinition]:
    if isinstance(obj, BoardKind | KitDefinition):
        return [obj]
    if isinstance(obj, Iterable) and not isinstance(obj, str | bytes):
        items = list(obj)
        if all(isinstance(item, BoardKind | KitDefinition) for item in items):
            return items
    raise TypeError(
        "the entry point must give a BoardKind, a KitDefinition, an iterable of them, or "
        f"a callable returning one of those; it gave {obj!r}"
    )


def _with_package(item: BoardKind | KitDefinition, package: str) -> BoardKind | KitDefinition:
    if item.package != "j5aio":
        return item
    if isinstance(item, KitDefinition):
        return replace(item, package=package)
    # (the board and backends as given: reading them would import those named by path)
    given = {role: vars(item)[f"_{role}"] for role in (*_BACKEND_ROLES, "board")}
    return replace(item, package=package, **given)


_registry = _Registry()

# The definitions are documented as j5aio.board_kinds's, where programs and plugins find
# them (that module is the registry's public face).
for _public in (
    BackendField, BoardField, BoardKind, BoardPluginWarning, KitDefinition, SimulatorClass,
    SimulatorEntry,
):
    _public.__module__ = "j5aio.board_kinds"
del _public

def board_kinds() -> tuple[BoardKind, ...]:
    """Every registered board kind: j5aio's own, then the plugins', in registration order."""
    return _registry.kinds()


def register(item: BoardKind | KitDefinition) -> None:
    """Register a board kind or a named kit from code (plugins use the entry point group).

    Environments made before (the hardware and simulated environments are made on first
    import) do not see it; it suits tests and programs that register before importing them.

    :raises TypeError: ``item`` is neither a :class:`BoardKind` nor a :class:`KitDefinition`.
    :raises ValueError: its name, or one of its simulators' names, is taken.
    """
    if not isinstance(item, BoardKind | KitDefinition):
        raise TypeError(f"register takes a BoardKind or a KitDefinition, not {type(item).__name__}")
    _registry.add(item)


def unregister(name: str) -> None:
    """Forget the board kind or kit called ``name``.

    :raises KeyError: nothing of that name is registered.
    """
    _registry.remove(name)


def simulator_entries() -> Mapping[str, tuple[BoardKind, SimulatorEntry]]:
    """Every registered simulator by command-line name, with the kind it simulates."""
    return MappingProxyType(
        {entry.name: (kind, entry) for kind in board_kinds() for entry in kind.simulators}
    )


def find_simulator(name: str) -> tuple[BoardKind, SimulatorEntry]:
    """Return the kind and simulator entry called ``name``.

    :raises ValueError: no simulator has that name; the message lists those that do.
    """
    entries = simulator_entries()
    try:
        return entries[name]
    except KeyError:
        raise ValueError(
            f"there is no simulator called {name!r}; choose one of: {', '.join(entries)}"
        ) from None


def kits() -> Mapping[str, KitDefinition]:
    """Every named simulated kit, with the boards plugins added to it."""
    return MappingProxyType(_registry.kits())


def get_kit(name: str) -> KitDefinition:
    """Return the kit called ``name``.

    :raises TypeError: ``name`` is not a string.
    :raises ValueError: there is no such kit (the message lists the kits), or it names a
        simulator that is not registered.
    """
    if not isinstance(name, str):
        raise TypeError(f"a kit name must be a str, not {type(name).__name__}")
    known = kits()
    kit = known.get(name.strip().lower())
    if kit is None:
        raise ValueError(f"there is no kit called {name!r}; choose one of: {', '.join(known)}")
    entries = simulator_entries()
    missing = [simulator for simulator in kit.boards if simulator not in entries]
    if missing:
        raise ValueError(
            f"kit {kit.name!r} needs simulators that are not registered: {', '.join(missing)}"
        )
    return kit

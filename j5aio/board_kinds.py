"""The registry of board kinds: every kind of board j5aio (or a plugin) knows how to drive.

A :class:`BoardKind` is one generation of one board: its board class, the hardware
backend that finds it, the simulators that stand in for it (each with a command-line
name), its console backend, and the named simulated kits it belongs to. Everything that
needs a list of boards reads it from here:

- the hardware environment and ``python -m j5aio list`` (hardware backends);
- :func:`j5aio.backends.hardware.attach <j5aio.backends.hardware.identify.attach>` (serial backends'
  identification);
- the simulated environment, ``J5AIO_ENV=sim`` and ``run --sim`` (simulators);
- ``python -m j5aio simulate NAME`` (serial simulators, by name);
- the named kits (``--kit NAME``, ``J5AIO_KIT``, :func:`~j5aio.simulator.kit.use_kit`);
- the console environment (console backends).

j5aio's own boards are registered in ``j5aio._builtin_kinds``. Other packages register
theirs through the ``j5aio.boards`` entry point group (:data:`ENTRY_POINT_GROUP`). An
entry point names an object that is one of:

- a :class:`BoardKind`;
- a :class:`KitDefinition` (a named simulated kit);
- an iterable of those;
- a callable taking no arguments that returns any of the above.

For example, in a plugin's ``pyproject.toml``::

    [project.entry-points."j5aio.boards"]
    beekit = "beekit.kinds:entries"

Plugins are loaded the first time the registry is read. A plugin that cannot be loaded,
or that returns something else, or that reuses a name already taken, is left out with a
:class:`BoardPluginWarning` naming the package and the entry point; j5aio itself carries
on.

This registry is not :mod:`j5aio.backends.hardware.registry`, which records which
board holds each open port.
"""

from __future__ import annotations

import importlib
import warnings
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field, replace
from types import MappingProxyType
from typing import Any, Final, cast, overload

from j5aio import _entry_points
from j5aio.backends.backend import Backend
from j5aio.boards.board import Board

__all__ = [
    "DEFAULT_KIT",
    "ENTRY_POINT_GROUP",
    "BackendField",
    "BoardKind",
    "BoardPluginWarning",
    "KitDefinition",
    "SimulatorClass",
    "SimulatorEntry",
    "SimulatorFactory",
    "board_kinds",
    "find_simulator",
    "get_kit",
    "kits",
    "register",
    "simulator_entries",
    "unregister",
]

#: The entry point group through which other packages register board kinds and kits.
ENTRY_POINT_GROUP: Final = "j5aio.boards"

#: The name of the kit the simulated environment uses when none is chosen.
DEFAULT_KIT: Final = "default"

SimulatorFactory = Callable[[str], object]
"""Makes a simulator given the serial number it reports: a
:class:`~j5aio.simulator.base.SerialBoardSimulator` (which ``simulate`` can serve on a
pty), a :class:`~j5aio.simulator.base.UsbBoardSimulator`, or, for a board reached
otherwise (a HAT's GPIO), a simulator of its own that the kind's ``simulated`` backend
finds in the kit."""


class BoardPluginWarning(UserWarning):
    """A plugin's entry in the ``j5aio.boards`` entry point group was left out."""


def _check_name(what: str, name: object) -> str:
    if not isinstance(name, str) or not name or name != name.strip() or " " in name:
        raise ValueError(f"a {what} name must be a non-empty string without spaces, not {name!r}")
    return name


class SimulatorClass:
    """A simulator factory naming its class by import path: imported on first use.

    ``SimulatorClass("package.module:ClassName")`` makes ``ClassName(serial_number)``
    when called, importing the module the first time, so that registering a
    :class:`SimulatorEntry` imports no simulator.

    :param path: the class's import path, ``"package.module:ClassName"``.
    :raises ValueError: ``path`` is not of that form.
    """

    __slots__ = ("_class", "path")

    def __init__(self, path: str) -> None:
        module, _, name = path.partition(":") if isinstance(path, str) else ("", "", "")
        if not module or not name.isidentifier():
            raise ValueError(
                f"a simulator class's import path is 'package.module:ClassName', not {path!r}"
            )
        #: The class's import path.
        self.path = path
        self._class: type | None = None

    def resolve(self) -> type:
        """Import and return the class.

        :raises ImportError: its module cannot be imported.
        :raises TypeError: the path names something other than a class.
        """
        if self._class is None:
            module, _, name = self.path.partition(":")
            found = getattr(importlib.import_module(module), name)
            if not isinstance(found, type):
                raise TypeError(f"{self.path} is not a class")
            self._class = found
        return self._class

    def __call__(self, serial_number: str) -> object:
        """Make the simulator with the serial number it reports."""
        return self.resolve()(serial_number)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, SimulatorClass) and other.path == self.path

    def __hash__(self) -> int:
        return hash(self.path)

    def __repr__(self) -> str:
        return f"SimulatorClass({self.path!r})"


@dataclass(frozen=True)
class SimulatorEntry:
    """A simulator of a board kind, as the command line and the simulated kits know it.

    :param name: the command-line name, e.g. ``"sr-motor"`` (``simulate NAME``, kits).
    :param factory: makes the simulator, given its serial number: a simulator class, a
        function, or a :class:`SimulatorClass` (a class named by its import path,
        imported on first use).
    :param description: what it is, for people (``"SR v4 motor board, firmware 3"``).
    :param serial_prefix: the start of the serial numbers of this simulator's boards in
        a simulated kit (``"SIMMB"`` gives ``SIMMB0``, ``SIMMB1``...).
    :param kits: the named kits this simulator joins, with how many boards of it each
        gets: ``{"default": 1}`` puts one in the default kit. A plugin uses this to add
        its board to j5aio's kits.
    :raises ValueError: a name is empty or has spaces, or a count is negative.
    """

    name: str
    factory: SimulatorFactory
    description: str
    serial_prefix: str
    kits: Mapping[str, int] = field(default_factory=dict)

    def __post_init__(self) -> None:
        _check_name("simulator", self.name)
        _check_name("serial prefix", self.serial_prefix)
        if not callable(self.factory):
            raise TypeError(f"the factory of simulator {self.name!r} must be callable")
        for kit, count in self.kits.items():
            if isinstance(count, bool) or not isinstance(count, int) or count < 0:
                raise ValueError(
                    f"simulator {self.name!r} joins kit {kit!r} with {count!r} boards: "
                    "give a whole number of 0 or more"
                )

    @property
    def is_serial(self) -> bool:
        """Whether the simulator speaks over a serial port (and so can be served on a pty)."""
        from j5aio.simulator.base import SerialBoardSimulator

        factory = self.factory
        if isinstance(factory, SimulatorClass):
            factory = factory.resolve()
        if isinstance(factory, type):
            return issubclass(factory, SerialBoardSimulator)
        return isinstance(self.factory("SIM0"), SerialBoardSimulator)


_BACKEND_ROLES: Final = ("hardware", "console", "simulated")


def _check_reference(kind: str, role: str, reference: str) -> None:
    module, _, name = reference.partition(":")
    if not module or not name.isidentifier():
        raise ValueError(
            f"board kind {kind!r}: its {role} backend {reference!r} must be a Backend "
            "subclass or its import path, 'package.module:ClassName'"
        )


class BackendField:
    """A backend attribute of :class:`BoardKind` (``hardware``, ``console``, ``simulated``).

    It is given a :class:`~j5aio.backends.backend.Backend` subclass, ``None``, or the
    class's import path (``"package.module:ClassName"``); read, it gives the class (or
    ``None``), importing and checking it the first time.
    """

    def __set_name__(self, owner: type, name: str) -> None:
        self._role = name
        self._slot = f"_{name}"

    @overload
    def __get__(self, kind: None, owner: type) -> None: ...

    @overload
    def __get__(self, kind: BoardKind, owner: type) -> type[Backend] | None: ...

    def __get__(self, kind: BoardKind | None, owner: type) -> type[Backend] | None:
        if kind is None:
            return None  # the dataclass's default
        value: type[Backend] | str | None = vars(kind)[self._slot]
        if isinstance(value, str):
            module, _, name = value.partition(":")
            backend = getattr(importlib.import_module(module), name)
            kind._check_backend(self._role, backend)
            object.__setattr__(kind, self._slot, backend)
            return cast("type[Backend]", backend)
        return value

    def __set__(self, kind: BoardKind, value: type[Backend] | str | None) -> None:
        vars(kind)[self._slot] = value


@dataclass(frozen=True)
class BoardKind:
    """One generation of one board, and everything that drives or stands in for it.

    Each of ``hardware``, ``console`` and ``simulated`` may be given as the backend's
    import path, ``"package.module:ClassName"``, instead of the class: the module is then
    imported the first time the attribute is read (a program on the simulated kit never
    imports the console backends, say). It is checked then as a class would be checked
    here, raising :class:`TypeError` or :class:`ImportError`.

    :param name: a unique name, e.g. ``"sr-v4-motor-fw3"``.
    :param board: the board class programs ask for (a subclass of the family's class for
        a new generation of a board family, or the family's class itself).
    :param description: what it is, for people.
    :param hardware: the hardware backend whose ``discover(options=...)`` finds it (a
        :class:`~j5aio.backends.hardware.serial_backend.SerialHardwareBackend` or
        :class:`~j5aio.backends.hardware.usb_backend.USBHardwareBackend` subclass), or
        ``None`` for a board with no hardware.
    :param console: its console backend, or ``None``.
    :param simulators: its simulators.
    :param simulated: the backend the simulated environment uses; by default the
        hardware backend, finding the boards of the current simulated kit made from
        this kind's simulators.
    :param identify_order: where this kind's serial backend comes in
        :func:`~j5aio.backends.hardware.identify.attach` and in telling apart boards that share
        USB IDs: lower first. Put a kind whose identification is quick and harmless to
        other boards first.
    :param package: the distribution that registered it (filled in for plugins).
    """

    name: str
    board: type[Board]
    description: str
    hardware: BackendField = BackendField()
    console: BackendField = BackendField()
    simulators: tuple[SimulatorEntry, ...] = ()
    simulated: BackendField = BackendField()
    identify_order: int = 100
    package: str = "j5aio"

    def __post_init__(self) -> None:
        _check_name("board kind", self.name)
        if not (isinstance(self.board, type) and issubclass(self.board, Board)):
            raise TypeError(f"board kind {self.name!r}: board must be a Board subclass")
        for role in _BACKEND_ROLES:
            backend = vars(self)[f"_{role}"]
            if isinstance(backend, str):
                _check_reference(self.name, role, backend)
            else:
                self._check_backend(role, backend)
        object.__setattr__(self, "simulators", tuple(self.simulators))
        for entry in self.simulators:
            if not isinstance(entry, SimulatorEntry):
                raise TypeError(f"board kind {self.name!r}: simulators must be SimulatorEntry")

    def backend_reference(self, role: str) -> str | None:
        """The import path of the ``role`` backend, ``"package.module:ClassName"``, or ``None``.

        It imports nothing: an environment uses it to know which kinds have a backend
        before it needs any of them.

        :param role: ``"hardware"``, ``"console"`` or ``"simulated"``.
        :raises ValueError: ``role`` is none of those.
        """
        if role not in _BACKEND_ROLES:
            raise ValueError(f"a backend role is one of {', '.join(_BACKEND_ROLES)}, not {role!r}")
        value: type[Backend] | str | None = vars(self)[f"_{role}"]
        if value is None or isinstance(value, str):
            return value
        return f"{value.__module__}:{value.__qualname__}"

    def _check_backend(self, role: str, backend: object) -> None:
        if backend is None:
            return
        if not (isinstance(backend, type) and issubclass(backend, Backend)):
            raise TypeError(f"board kind {self.name!r}: {role} must be a Backend subclass")
        if not issubclass(backend.board, self.board):
            raise TypeError(
                f"board kind {self.name!r}: its {role} backend {backend.__name__} drives "
                f"{backend.board.__name__}, not {self.board.__name__}"
            )


@dataclass(frozen=True)
class KitDefinition:
    """A named simulated kit: how many boards of each simulator it has, and how they are wired.

    ::

        KitDefinition(
            "ourbot", "our robot", {"sr-power-fw4": 1, "sr-motor-fw4": 2},
            serials={"sr-motor-fw4": ("SR0UK1L", "SR0AB12")},
            wiring={"sr-motor-fw4": ("H0", "H1")},
        )

    :param name: the kit's name, e.g. ``"sr2019"``.
    :param description: what it is, for people.
    :param boards: simulator names (each :class:`~j5aio.board_kinds.SimulatorEntry`'s ``name``) and
        how many of each, in the order the kit makes them.
    :param package: the distribution that registered it (filled in for plugins).
    :param wiring: for a simulator whose boards take 12 V from the power board (motor
        and servo boards), the power output feeding each of its boards, in order: a name
        (``"H0"``, ``"H1"``, ``"L0"``, ``"L1"``, ``"L3"``, ``"5V"``) or a number (0-6).
        Simulators left out are wired by the default rule
        (:func:`j5aio.simulator.wiring.default_outputs`).
    :param serials: the serial numbers of a simulator's boards, in order; simulators
        left out number their boards from the simulator's serial prefix (``SIMMB0``...).
    :raises ValueError: a count is not a whole number of 0 or more; ``wiring`` or
        ``serials`` name a simulator the kit does not have, give another number of
        entries than it has boards, or repeat a serial number; an output does not exist
        or is L2 (the brain's).
    """

    name: str
    description: str
    boards: Mapping[str, int]
    package: str = "j5aio"
    wiring: Mapping[str, tuple[int | str, ...]] = field(default_factory=dict)
    serials: Mapping[str, tuple[str, ...]] = field(default_factory=dict)

    def __post_init__(self) -> None:
        _check_name("kit", self.name)
        object.__setattr__(self, "boards", MappingProxyType(dict(self.boards)))
        for simulator, count in self.boards.items():
            if isinstance(count, bool) or not isinstance(count, int) or count < 0:
                raise ValueError(
                    f"kit {self.name!r} has {count!r} of {simulator!r}: give a whole number "
                    "of 0 or more"
                )
        wiring = self._per_board("wiring", self.wiring)
        for simulator, outputs in wiring.items():
            for output in outputs:
                _check_fed_output(self.name, simulator, output)
        serials = self._per_board("serials", self.serials)
        seen: set[str] = set()
        for simulator, numbers in serials.items():
            for number in numbers:
                if not isinstance(number, str) or not number.strip() or " " in number:
                    raise ValueError(
                        f"kit {self.name!r}: a serial number of {simulator!r} must be a "
                        f"non-empty string without spaces, not {number!r}"
                    )
                if number in seen:
                    raise ValueError(
                        f"kit {self.name!r}: serial number {number!r} is given twice; each "
                        "board's must be its own"
                    )
                seen.add(number)
        object.__setattr__(self, "wiring", MappingProxyType(wiring))
        object.__setattr__(self, "serials", MappingProxyType(serials))

    def _per_board(self, what: str, given: Mapping[str, object]) -> dict[str, tuple[Any, ...]]:
        result: dict[str, tuple[Any, ...]] = {}
        for simulator, values in dict(given).items():
            if simulator not in self.boards:
                raise ValueError(
                    f"kit {self.name!r}: its {what} names {simulator!r}, which the kit has "
                    f"no boards of; it has {', '.join(self.boards) or 'none'}"
                )
            items = (values,) if isinstance(values, str | int) else tuple(cast(Any, values))
            if len(items) != self.boards[simulator]:
                raise ValueError(
                    f"kit {self.name!r}: its {what} give {len(items)} for {simulator!r}, "
                    f"which the kit has {self.boards[simulator]} of: give one for each board"
                )
            result[simulator] = items
        return result


def _check_fed_output(kit: str, simulator: str, output: object) -> None:
    from j5aio.power_outputs import BRAIN_OUTPUT, output_number

    if not isinstance(output, int | str) or isinstance(output, bool):
        raise ValueError(
            f"kit {kit!r}: {simulator!r} is wired to {output!r}: give an output's name "
            "(H0, H1, L0, L1, L3, 5V) or number"
        )
    try:
        number = output_number(output)
    except ValueError as error:
        raise ValueError(f"kit {kit!r}: {simulator!r}: {error}") from None
    if number == BRAIN_OUTPUT:
        raise ValueError(
            f"kit {kit!r}: {simulator!r} cannot be wired to L2: that output powers the brain"
        )


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
            from j5aio import _builtin_kinds

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
    # (the backends as given: reading them would import those named by path)
    given = {role: vars(item)[f"_{role}"] for role in _BACKEND_ROLES}
    return replace(item, package=package, **given)


_registry = _Registry()


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

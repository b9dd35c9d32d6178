"""The definitions the board kind registry holds: board kinds, their simulators and named kits.

Every name here is public in :mod:`j5aio.board_kinds`, and documented there; this module
holds them so that j5aio's own kinds (``j5aio.backends._builtin_kinds``) can be written
without importing the registry that loads them.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import field
from types import MappingProxyType
from typing import Any, Final, Literal, cast, overload

from j5aio._records import FrozenRecord, frozen_record
from j5aio.backends.backend import Backend
from j5aio.boards.board import Board
from j5aio.import_paths import check_import_path, import_class
from j5aio.power_outputs import BRAIN_OUTPUT, output_number

__all__ = [
    "DEFAULT_KIT",
    "BackendField",
    "BoardField",
    "BoardKind",
    "KitDefinition",
    "SimulatorClass",
    "SimulatorEntry",
    "SimulatorFactory",
    "SimulatorTransport",
]

#: The name of the kit the simulated environment uses when none is chosen.
DEFAULT_KIT: Final = "default"

SimulatorFactory = Callable[[str], object]
"""Makes a simulator given the serial number it reports: a
:class:`~j5aio.simulator.base.SerialBoardSimulator` (which ``simulate`` can serve on a
pty), a :class:`~j5aio.simulator.base.UsbBoardSimulator`, or, for a board reached
otherwise (a HAT's GPIO), a simulator of its own that the kind's ``simulated`` backend
finds in the kit."""


def _check_name(what: str, name: object) -> str:
    if not isinstance(name, str) or not name or name != name.strip() or " " in name:
        raise ValueError(f"a {what} name must be a non-empty string without spaces, not {name!r}")
    return name


SimulatorTransport = Literal["serial", "usb", "other"]
"""How a simulator's board is reached: ``"serial"`` (a
:class:`~j5aio.simulator.base.SerialBoardSimulator`, which ``simulate`` can serve on a pty),
``"usb"`` (a :class:`~j5aio.simulator.base.UsbBoardSimulator`) or ``"other"`` (a HAT's GPIO,
say)."""

_TRANSPORTS: Final = ("serial", "usb", "other")

# The dataclasses below write their own ``__init__`` and take freezing, ``__repr__``,
# ``__eq__`` and ``__hash__`` from FrozenRecord (as ``@dataclass(frozen=True)`` would make
# them): every program imports this module, and the generated ones cost a quarter of a
# millisecond a class to make. A test checks each against the dataclass the decorator
# alone would make.


class _NewDict:
    """The default of a mapping field: a new empty dict each time (shown as ``{}``)."""

    __slots__ = ()

    def __repr__(self) -> str:
        return "{}"


_NEW_DICT: Any = _NewDict()


class SimulatorClass:
    """A simulator factory naming its class by import path: imported on first use.

    ``SimulatorClass("package.module:ClassName")`` makes ``ClassName(serial_number)``
    when called, importing the module the first time, so that registering a
    :class:`SimulatorEntry` imports no simulator.

    :param path: the class's import path, ``"package.module:ClassName"``.
    :param serial_keyword: the keyword the class takes the serial number as, if it does
        not take it as its first argument.
    :param keywords: more keyword arguments for the class (a firmware version, say).
    :raises ValueError: ``path`` is not of that form.
    """

    __slots__ = ("_class", "keywords", "path", "serial_keyword")

    def __init__(self, path: str, *, serial_keyword: str | None = None, **keywords: Any) -> None:
        #: The class's import path.
        self.path = check_import_path(path, "a simulator class")
        #: The keyword the serial number is given as (``None``: the first argument).
        self.serial_keyword = serial_keyword
        #: The other keyword arguments the class is made with.
        self.keywords: Mapping[str, Any] = MappingProxyType(dict(keywords))
        self._class: type | None = None

    def resolve(self) -> type:
        """Import and return the class.

        :raises ImportError: its module cannot be imported.
        :raises TypeError: the path names something other than a class.
        """
        if self._class is None:
            self._class = import_class(self.path, "a simulator class")
        return self._class

    def __call__(self, serial_number: str) -> object:
        """Make the simulator with the serial number it reports."""
        if self.serial_keyword is None:
            return self.resolve()(serial_number, **self.keywords)
        return self.resolve()(**{self.serial_keyword: serial_number, **self.keywords})

    def _key(self) -> tuple[object, ...]:
        return (self.path, self.serial_keyword, tuple(sorted(self.keywords.items())))

    def __eq__(self, other: object) -> bool:
        return isinstance(other, SimulatorClass) and other._key() == self._key()

    def __hash__(self) -> int:
        return hash(self._key())

    def __repr__(self) -> str:
        extras = "".join(
            f", {name}={value!r}"
            for name, value in (
                ([("serial_keyword", self.serial_keyword)] if self.serial_keyword else [])
                + list(self.keywords.items())
            )
        )
        return f"SimulatorClass({self.path!r}{extras})"


@frozen_record
class SimulatorEntry(FrozenRecord):
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
    :param transport: how the board is reached (a keyword, required):
        ``"serial"``, ``"usb"`` or ``"other"`` (:data:`SimulatorTransport`). It is
        declared so that nothing is imported or made to learn it.
    :raises ValueError: a name is empty or has spaces, a count is negative, or the
        transport is none of those.
    """

    name: str
    factory: SimulatorFactory
    description: str
    serial_prefix: str
    kits: Mapping[str, int] = field(default_factory=dict)
    transport: SimulatorTransport = field(kw_only=True)

    def __init__(
        self,
        name: str,
        factory: SimulatorFactory,
        description: str,
        serial_prefix: str,
        kits: Mapping[str, int] = _NEW_DICT,
        *,
        transport: SimulatorTransport,
    ) -> None:
        set_field = object.__setattr__
        set_field(self, "name", name)
        set_field(self, "factory", factory)
        set_field(self, "description", description)
        set_field(self, "serial_prefix", serial_prefix)
        set_field(self, "kits", {} if kits is _NEW_DICT else kits)
        set_field(self, "transport", transport)
        self.__post_init__()

    def __post_init__(self) -> None:
        _check_name("simulator", self.name)
        _check_name("serial prefix", self.serial_prefix)
        if not callable(self.factory):
            raise TypeError(f"the factory of simulator {self.name!r} must be callable")
        if self.transport not in _TRANSPORTS:
            raise ValueError(
                f"simulator {self.name!r}: its transport is one of "
                f"{', '.join(map(repr, _TRANSPORTS))}, not {self.transport!r}"
            )
        for kit, count in self.kits.items():
            if isinstance(count, bool) or not isinstance(count, int) or count < 0:
                raise ValueError(
                    f"simulator {self.name!r} joins kit {kit!r} with {count!r} boards: "
                    "give a whole number of 0 or more"
                )

    @property
    def is_serial(self) -> bool:
        """Whether the simulator speaks over a serial port (and so can be served on a pty)."""
        return self.transport == "serial"


_BACKEND_ROLES: Final = ("hardware", "console", "simulated")


def _what(kind: str, role: str) -> str:
    return f"board kind {kind!r}: its {role} backend"


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
            backend = import_class(value, _what(kind.name, self._role))
            kind._check_backend(self._role, backend)
            object.__setattr__(kind, self._slot, backend)
            return cast("type[Backend]", backend)
        return value

    def __set__(self, kind: BoardKind, value: type[Backend] | str | None) -> None:
        vars(kind)[self._slot] = value


class BoardField:
    """The ``board`` attribute of :class:`BoardKind`.

    It is given a :class:`~j5aio.boards.board.Board` subclass or the class's import path
    (``"package.module:ClassName"``); read, it gives the class, importing and checking it
    the first time. It has no default.
    """

    def __get__(self, kind: BoardKind | None, owner: type) -> type[Board]:
        if kind is None:  # (no default: the dataclass asks, and learns there is none)
            raise AttributeError("board")
        value: type[Board] | str = vars(kind)["_board"]
        if isinstance(value, str):
            board = import_class(value, f"board kind {kind.name!r}: its board")
            _check_board(kind.name, board)
            vars(kind)["_board"] = board
            return cast("type[Board]", board)
        return value

    def __set__(self, kind: BoardKind, value: type[Board] | str) -> None:
        vars(kind)["_board"] = value


def _check_board(kind: str, board: object) -> None:
    if not (isinstance(board, type) and issubclass(board, Board)):
        raise TypeError(f"board kind {kind!r}: board must be a Board subclass")


@frozen_record
class BoardKind(FrozenRecord):
    """One generation of one board, and everything that drives or stands in for it.

    Each of ``hardware``, ``console`` and ``simulated`` may be given as the backend's
    import path, ``"package.module:ClassName"``, instead of the class: the module is then
    imported the first time the attribute is read (a program on the simulated kit never
    imports the console backends, say). It is checked then as a class would be checked
    here, raising :class:`TypeError` or :class:`ImportError`.

    :param name: a unique name, e.g. ``"sr-v4-motor-fw3"``.
    :param board: the board class programs ask for (a subclass of the family's class for
        a new generation of a board family, or the family's class itself), or its import
        path, ``"package.module:ClassName"``: the module is then imported the first time
        the attribute is read, and the class checked then.
    :param description: what it is, for people.
    :param hardware: the hardware backend whose ``discover(options=...)`` finds it (a
        :class:`~j5aio.backends.hardware.serial_backend.SerialHardwareBackend` or
        :class:`~j5aio.backends.hardware.usb_backend.USBHardwareBackend` subclass), or
        ``None`` for a board with no hardware.
    :param console: its console backend, or ``None``.
    :param simulators: its simulators.
    :param simulated: the backend the simulated environment uses, required when the kind
        has simulators: for a serial or USB board, a subclass of the hardware backend
        whose ``discover`` finds the boards of the current simulated kit made from this
        kind's simulators (see :mod:`j5aio.simulator.sim_backends`), and nothing else.
    :param identify_order: where this kind's serial backend comes in
        :func:`~j5aio.backends.hardware.identify.attach` and in telling apart boards that share
        USB IDs: lower first. Put a kind whose identification is quick and harmless to
        other boards first.
    :param package: the distribution that registered it (filled in for plugins).
    """

    name: str
    # (no default, though mypy sees one: the descriptor says there is none)
    board: BoardField = BoardField()
    description: str  # type: ignore[misc]
    hardware: BackendField = BackendField()
    console: BackendField = BackendField()
    simulators: tuple[SimulatorEntry, ...] = ()
    simulated: BackendField = BackendField()
    identify_order: int = 100
    package: str = "j5aio"

    def __init__(
        self,
        name: str,
        board: type[Board] | str,
        description: str,
        hardware: type[Backend] | str | None = None,
        console: type[Backend] | str | None = None,
        simulators: tuple[SimulatorEntry, ...] = (),
        simulated: type[Backend] | str | None = None,
        identify_order: int = 100,
        package: str = "j5aio",
    ) -> None:
        set_field = object.__setattr__  # (the board and backends through their descriptors)
        set_field(self, "name", name)
        set_field(self, "board", board)
        set_field(self, "description", description)
        set_field(self, "hardware", hardware)
        set_field(self, "console", console)
        set_field(self, "simulators", simulators)
        set_field(self, "simulated", simulated)
        set_field(self, "identify_order", identify_order)
        set_field(self, "package", package)
        self.__post_init__()

    def __post_init__(self) -> None:
        _check_name("board kind", self.name)
        board = vars(self)["_board"]
        if isinstance(board, str):
            check_import_path(board, f"board kind {self.name!r}: its board")
        else:
            _check_board(self.name, board)
        for role in _BACKEND_ROLES:
            backend = vars(self)[f"_{role}"]
            if isinstance(backend, str):
                check_import_path(backend, _what(self.name, role))
            else:
                self._check_backend(role, backend)
        object.__setattr__(self, "simulators", tuple(self.simulators))
        for entry in self.simulators:
            if not isinstance(entry, SimulatorEntry):
                raise TypeError(f"board kind {self.name!r}: simulators must be SimulatorEntry")
        if self.simulators and vars(self)["_simulated"] is None:
            raise ValueError(
                f"board kind {self.name!r} has simulators but names no simulated backend: "
                "give simulated=, the backend that finds its simulators in the simulated kit"
            )

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

    def board_reference(self) -> str:
        """The import path of the board class, ``"package.module:ClassName"``.

        It imports nothing (see :meth:`backend_reference`).
        """
        value: type[Board] | str = vars(self)["_board"]
        return value if isinstance(value, str) else f"{value.__module__}:{value.__qualname__}"

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


@frozen_record
class KitDefinition(FrozenRecord):
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

    def __init__(
        self,
        name: str,
        description: str,
        boards: Mapping[str, int],
        package: str = "j5aio",
        wiring: Mapping[str, tuple[int | str, ...]] = _NEW_DICT,
        serials: Mapping[str, tuple[str, ...]] = _NEW_DICT,
    ) -> None:
        set_field = object.__setattr__
        set_field(self, "name", name)
        set_field(self, "description", description)
        set_field(self, "boards", boards)
        set_field(self, "package", package)
        set_field(self, "wiring", {} if wiring is _NEW_DICT else wiring)
        set_field(self, "serials", {} if serials is _NEW_DICT else serials)
        self.__post_init__()

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

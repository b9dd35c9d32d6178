"""The simulated kit: which board simulators exist, and which kit is in use now.

A kit is made from a named kit of the registry (:func:`j5aio.board_kinds.kits`:
``"default"``, ``"sr2019"``, ``"sb2019"`` and any a plugin adds) or from a
:class:`KitConfig`, which says how many of each seed-generation board the kit has. A
:class:`SimulatedKit` holds one simulator per board, each with its own serial number, so
that a program or a test can look at what the boards are doing::

    kit = use_kit(KitConfig(motor_boards=1))
    kit = use_kit("sr2019")                 # or a named kit
    ...  # run a robot on the simulated environment
    kit.motor_boards[0].motors[0].mode      # MotorMode.BRAKE

The simulated environment (:mod:`j5aio.simulator.environment`) finds the boards of the
kit returned by :func:`current_kit`. Without a call to :func:`use_kit` that is the kit
named by the ``J5AIO_KIT`` environment variable, or else the default kit: one power
board, two motor boards, one servo board and one SourceBots Arduino.

Simulators are plain state machines: read their state from the thread that runs the
event loop, between awaits.
"""

from __future__ import annotations

import itertools
import os
import sys
from collections.abc import Iterator
from typing import TYPE_CHECKING, Any, Final, TypeGuard, cast

from j5aio.board_kinds import DEFAULT_KIT, BoardKind, KitDefinition, get_kit, simulator_entries
from j5aio.power_outputs import output_number

from . import _kit_counts
from ._kit_counts import check_count, check_time_scale
from .base import SerialBoardSimulator, UsbBoardSimulator
from .clock import Clock, drive, kit_clock
from .wiring import KitWiring, PowerFed, default_outputs, is_power_board, is_power_fed

if TYPE_CHECKING:
    from ._kit_config import KitConfig
    from .arena import SimulatedWorld
    from .camera import SimulatedCamera
    from .sb_arduino_2019 import SBArduinoSimulator
    from .sr_motor_fw3 import SRMotorBoardFw3Simulator
    from .sr_motor_fw4 import SRMotorBoardFw4Simulator
    from .sr_power_fw3 import SRPowerBoardFw3Simulator
    from .sr_ruggeduino_fw1 import SRRuggeduinoSimulator
    from .sr_servo_fw2 import SRServoBoardFw2Simulator

__all__ = [
    "KIT_VARIABLE",
    "BoardSimulator",
    "KitConfig",
    "SimulatedKit",
    "current_kit",
    "kit_from_environment",
    "use_kit",
]

#: The most boards of one kind a simulated kit may have.
MAX_BOARDS_OF_A_KIND: Final = _kit_counts.MAX_BOARDS_OF_A_KIND

#: The environment variable that names the kit of the simulated environment.
KIT_VARIABLE: Final = "J5AIO_KIT"

# The kit file's variable (:data:`j5aio.simulator.kit_file.KIT_FILE_VARIABLE`), read here
# so that a program without a kit file does not import the kit file's reader.
_KIT_FILE_VARIABLE: Final = "J5AIO_KIT_FILE"

BoardSimulator = object
"""A simulator of one board: usually a :class:`~j5aio.simulator.base.SerialBoardSimulator`
or a :class:`~j5aio.simulator.base.UsbBoardSimulator`, but a board reached otherwise (a
Raspberry Pi HAT's GPIO, say) has a simulator of its own shape."""

_kit_numbers = itertools.count(1)

class SimulatedKit:
    """One simulator for each board of a kit.

    Serial numbers are distinct and sort in board order, so that ``kit.motor_boards[i]``
    is the board a robot sees as ``robot.motor_boards[i]``: each simulator's
    the ``serial_prefix`` of its :class:`~j5aio.board_kinds.SimulatorEntry` and the board's index,
    ``SIMPB0`` for the first power board, ``SIMMB0`` and ``SIMMB1`` for motor boards,
    ``SIMSB0`` for a servo board, ``SIMSBA0`` for a SourceBots Arduino and ``SIMRD0`` for a
    Ruggeduino (``SIMMB00`` to ``SIMMB11`` in a kit of twelve motor boards).

    A registry kit may give its boards' serial numbers instead
    (:attr:`KitDefinition.serials <j5aio.board_kinds.KitDefinition>`), as a kit file
    does (:mod:`j5aio.simulator.kit_file`).

    Power wiring: in a *wired* kit the motor and servo boards take their 12 V from the
    power board's outputs, as on the robot (:mod:`j5aio.simulator.wiring`): the outputs
    start off, so these boards have no power until a program switches their outputs on
    (:class:`~j5aio.kit.KitRobot` does, as sr-robot3 and sbot do). The kit definition
    says which output feeds which board, else the default rule does (motor boards on H0,
    H1; servo boards on L0). ``wired`` says when the kit is wired:

    - ``True``: from the start. The kit a program runs on (``run --sim``,
      ``J5AIO_ENV=sim``, ``J5AIO_KIT``, a kit file, the demo) is wired so.
    - ``None`` (the default for a kit made in code): every board is powered until a
      robot starts on the kit (:meth:`wire`, which :class:`~j5aio.kit.KitRobot` calls),
      and wired from then on. So a test of one board's protocol finds its boards
      straight away, while a robot program meets the robot's wiring.
    - ``False``: never; every board is powered whatever the outputs do.

    A kit without a power board is never wired: its boards are always powered.

    :param config: the kit: a :class:`KitConfig`, a registry kit
        (:class:`~j5aio.board_kinds.KitDefinition`) or a kit's name; the default kit if
        omitted.
    :param time_scale: the time scale of a named kit (a :class:`KitConfig` has its own).
    :param wired: when to feed the boards from the power board's outputs (see above).
    :raises TypeError: ``config`` is none of those.
    :raises ValueError: there is no kit of that name (the message lists the kits), two
        of its simulators would share serial numbers, or a board is wired to an output
        its power board does not have.
    """

    def __init__(
        self,
        config: KitConfig | KitDefinition | str | None = None,
        *,
        time_scale: float | None = None,
        wired: bool | None = None,
    ) -> None:
        if config is None:
            config = DEFAULT_KIT
        if isinstance(config, str):
            config = get_kit(config)
        self._config: KitConfig | None
        if _is_kit_config(config):
            if time_scale is not None:
                raise TypeError("give the time scale in the KitConfig, not beside it")
            boards, self._definition = config.boards(), None
            self._config, self._time_scale = config, config.time_scale
        elif isinstance(config, KitDefinition):
            scale = 0.0 if time_scale is None else time_scale
            check_time_scale(scale)
            boards, self._definition = dict(config.boards), config
            # (checked as its KitConfig would check them; that is made when first read)
            for field_name, seed in _kit_counts.CONFIG_SIMULATORS.items():
                check_count(field_name, boards.get(seed, 0))
            self._config, self._time_scale = None, scale
            self._boards_asked = boards
        else:
            raise TypeError(
                "a kit is a KitConfig, a KitDefinition or a kit's name, not "
                f"{type(config).__name__}"
            )
        self._name = f"kit{next(_kit_numbers)}"
        #: The kit's clock, which its boards' firmware timers follow: real time divided by
        #: the time scale (:func:`~j5aio.simulator.clock.kit_clock`); see :meth:`use_clock`.
        self.clock: Clock = kit_clock(self._time_scale)
        # The world and the camera are made when first read (a robot that never looks
        # through its camera never needs the arena, nor the vision modules).
        self._world: SimulatedWorld | None = None
        self._camera: SimulatedCamera | _DefaultCamera | None = _DEFAULT_CAMERA
        self._made_default_camera: SimulatedCamera | None = None
        self._boards: dict[str, tuple[BoardSimulator, ...]] = {}
        self._kinds: dict[int, BoardKind] = {}
        entries = simulator_entries()
        prefixes: dict[str, str] = {}
        for simulator_name, count in boards.items():
            check_count(simulator_name, count)
            try:
                kind, entry = entries[simulator_name]
            except KeyError:
                raise ValueError(
                    f"the kit needs a simulator called {simulator_name!r}, which is not "
                    f"registered; there are: {', '.join(entries)}"
                ) from None
            if count and prefixes.setdefault(entry.serial_prefix, entry.name) != entry.name:
                raise ValueError(
                    f"simulators {prefixes[entry.serial_prefix]!r} and {entry.name!r} both "
                    f"number their boards {entry.serial_prefix}...: give one another prefix"
                )
            given = self._definition.serials.get(simulator_name) if self._definition else None
            serials = given or [_serial(entry.serial_prefix, i, count) for i in range(count)]
            made = tuple(entry.factory(serial) for serial in serials)
            self._boards[simulator_name] = made
            for simulator in made:
                self._kinds[id(simulator)] = kind
        self._check_distinct_serials()
        drive(self._all(), self.clock)
        self._wire_when_asked = wired is None
        self._wiring: KitWiring | None = self._wire() if wired else None

    def _check_distinct_serials(self) -> None:
        seen: set[str] = set()
        for simulator in self._all():
            serial = getattr(simulator, "serial_number", None)
            if isinstance(serial, str) and serial in seen:
                raise ValueError(
                    f"two boards of the kit have serial number {serial!r}: each board's "
                    "must be its own"
                )
            if isinstance(serial, str):
                seen.add(serial)

    def _wire(self) -> KitWiring | None:
        """Join the first power board to the boards it feeds (None without a power board)."""
        power_board = next((sim for sim in self._all() if is_power_board(sim)), None)
        if power_board is None:
            return None
        given = dict(self._definition.wiring) if self._definition is not None else {}
        feeds: list[tuple[PowerFed, int]] = []
        for name, made in self._boards.items():
            if name in given:
                outputs = [
                    output_number(output, count=power_board.OUTPUT_COUNT)
                    for output in given[name]
                ]
                feeds += [
                    (sim, out) for sim, out in zip(made, outputs, strict=True)
                    if is_power_fed(sim)
                ]
        chosen = {id(sim) for sim, _ in feeds}
        rest = [sim for sim in self._all() if is_power_fed(sim) and id(sim) not in chosen]
        taken = [out for _, out in feeds]
        feeds += zip(rest, default_outputs(rest, taken=taken), strict=True)
        order = {id(sim): index for index, sim in enumerate(self._all())}
        feeds.sort(key=lambda feed: order[id(feed[0])])
        return KitWiring(power_board, feeds)

    @property
    def world(self) -> SimulatedWorld:
        """The arena, the robot's pose and its drive (see :mod:`j5aio.simulator.arena`)."""
        if self._world is None:
            from .arena import SimulatedWorld

            self._world = SimulatedWorld()
        return self._world

    @world.setter
    def world(self, world: SimulatedWorld) -> None:
        self._world = world

    @property
    def has_world(self) -> bool:
        """Whether :attr:`world` has been made yet (reading it makes it)."""
        return self._world is not None

    @property
    def camera(self) -> SimulatedCamera | None:
        """The robot's camera, or ``None`` for a robot without one.

        A :class:`~j5aio.simulator.camera.SimulatedCamera`; set it to change or remove
        the camera.
        """
        if isinstance(self._camera, _DefaultCamera):
            self._camera = self.default_camera()
        return self._camera

    @camera.setter
    def camera(self, camera: SimulatedCamera | None) -> None:
        self._camera = camera

    @property
    def has_camera(self) -> bool:
        """Whether the robot has a camera (:attr:`camera` is not ``None``), making none."""
        return self._camera is not None

    def _camera_if_made(self) -> SimulatedCamera | None:
        """The camera, or ``None`` while it is the default camera and not made yet."""
        return None if isinstance(self._camera, _DefaultCamera) else self._camera

    def default_camera(self) -> SimulatedCamera:
        """The camera the kit was made with (made when first asked for, then kept).

        It is :attr:`camera` until that is set to another.
        """
        if self._made_default_camera is None:
            from ._camera_model import SimulatedCamera

            self._made_default_camera = SimulatedCamera()
        return self._made_default_camera

    @property
    def wiring(self) -> KitWiring | None:
        """The kit's power wiring, or ``None`` while it is not wired (see the class)."""
        return self._wiring

    def wire(self) -> KitWiring | None:
        """Wire a kit made with ``wired=None`` now (a robot starting on it calls this).

        From now on the boards take their power from the power board's outputs: those
        that are off leave the boards they feed without power. A kit wired already, or
        made with ``wired=False``, is left as it is.

        :returns: the kit's wiring, or ``None`` if it is not wired.
        """
        if self._wiring is None and self._wire_when_asked:
            self._wire_when_asked = False
            self._wiring = self._wire()
        return self._wiring

    def use_clock(self, clock: Clock) -> None:
        """Run every board's firmware timers on ``clock`` from now on (a test's manual one)."""
        self.clock = clock
        drive(self._all(), clock)

    @property
    def config(self) -> KitConfig:
        """The configuration of the kit's seed-generation boards, and its time scale."""
        if self._config is None:
            from ._kit_config import KitConfig

            self._config = KitConfig.from_boards(self._boards_asked, self._time_scale)
        return self._config

    @property
    def definition(self) -> KitDefinition | None:
        """The registry kit it was made from, or ``None`` if from a :class:`KitConfig`."""
        return self._definition

    @property
    def name(self) -> str:
        """A name unique to this kit in the program (``kit1``, ``kit2``...), used in port names."""
        return self._name

    @property
    def time_scale(self) -> float:
        """The factor applied to every simulated delay."""
        return self._time_scale

    def simulator_names(self) -> tuple[str, ...]:
        """The registry names of the simulators the kit was made from, in order."""
        return tuple(self._boards)

    def simulators(self, name: str) -> tuple[BoardSimulator, ...]:
        """The simulators made from the registry's simulator ``name`` (e.g. ``"sr-motor"``)."""
        return self._boards.get(name, ())

    def kind_of(self, simulator: BoardSimulator) -> BoardKind:
        """The board kind ``simulator`` stands in for.

        :raises KeyError: ``simulator`` is not one of this kit's.
        """
        try:
            return self._kinds[id(simulator)]
        except KeyError:
            raise KeyError(f"{simulator!r} is not a board of {self._name}") from None

    def _all(self) -> Iterator[BoardSimulator]:
        for made in self._boards.values():
            yield from made

    def _of_class(self, *classes: tuple[str, str]) -> list[Any]:
        """The kit's simulators of the classes named ``(module, class)`` in this package.

        A class's module is looked up, not imported: the kit has simulators of it only
        once the kit's factories have imported it (a kit of firmware-4 boards never
        imports the firmware-3 simulators, say).
        """
        loaded = tuple(
            getattr(sys.modules[f"{__package__}.{module}"], name)
            for module, name in classes
            if f"{__package__}.{module}" in sys.modules
        )
        return [sim for sim in self._all() if isinstance(sim, loaded)] if loaded else []

    @property
    def power_boards(self) -> tuple[SRPowerBoardFw3Simulator, ...]:
        """The simulated power boards."""
        return tuple(self._of_class(("sr_power_fw3", "SRPowerBoardFw3Simulator")))

    @property
    def motor_boards(self) -> tuple[SRMotorBoardFw3Simulator, ...]:
        """The simulated motor boards."""
        return tuple(self._of_class(("sr_motor_fw3", "SRMotorBoardFw3Simulator")))

    @property
    def drive_motor_boards(self) -> tuple[SRMotorBoardFw3Simulator | SRMotorBoardFw4Simulator, ...]:
        """Every simulated motor board, firmware 3 or 4, in the order a robot sees them.

        Each has ``motors[i].power``, the signed duty the board drives: the simulated world
        moves the robot by these (:func:`j5aio.simulator.camera.update_world`).
        """
        boards = cast(
            "list[SRMotorBoardFw3Simulator | SRMotorBoardFw4Simulator]",
            self._of_class(
                ("sr_motor_fw3", "SRMotorBoardFw3Simulator"),
                ("sr_motor_fw4", "SRMotorBoardFw4Simulator"),
            ),
        )
        return tuple(sorted(boards, key=lambda sim: sim.serial_number))

    @property
    def servo_boards(self) -> tuple[SRServoBoardFw2Simulator, ...]:
        """The simulated servo boards."""
        return tuple(self._of_class(("sr_servo_fw2", "SRServoBoardFw2Simulator")))

    @property
    def sb_arduinos(self) -> tuple[SBArduinoSimulator, ...]:
        """The simulated SourceBots Arduinos."""
        return tuple(self._of_class(("sb_arduino_2019", "SBArduinoSimulator")))

    @property
    def ruggeduinos(self) -> tuple[SRRuggeduinoSimulator, ...]:
        """The simulated Ruggeduinos."""
        return tuple(self._of_class(("sr_ruggeduino_fw1", "SRRuggeduinoSimulator")))

    def serial_simulators(self) -> tuple[SerialBoardSimulator, ...]:
        """Every board reached through a serial port."""
        return tuple(sim for sim in self._all() if isinstance(sim, SerialBoardSimulator))

    def usb_simulators(self) -> tuple[UsbBoardSimulator, ...]:
        """Every board reached through USB control transfers."""
        return tuple(sim for sim in self._all() if isinstance(sim, UsbBoardSimulator))

    def other_simulators(self) -> tuple[BoardSimulator, ...]:
        """Every board reached neither by serial port nor by USB (a HAT's GPIO, say)."""
        return tuple(
            sim
            for sim in self._all()
            if not isinstance(sim, SerialBoardSimulator | UsbBoardSimulator)
        )

    def __iter__(self) -> Iterator[SerialBoardSimulator | UsbBoardSimulator]:
        """Iterate over every board of the kit reached by USB or a serial port."""
        yield from self.usb_simulators()
        yield from self.serial_simulators()

    def __len__(self) -> int:
        """How many boards reached by USB or a serial port the kit has."""
        return len(self.usb_simulators()) + len(self.serial_simulators())

    def __repr__(self) -> str:
        what = self._definition.name if self._definition is not None else repr(self.config)
        return f"<SimulatedKit {self._name} {what}>"


def _is_kit_config(config: object) -> TypeGuard[KitConfig]:
    """Whether ``config`` is a :class:`KitConfig` (whose module is then loaded already)."""
    module = sys.modules.get("j5aio.simulator._kit_config")
    return module is not None and isinstance(config, module.KitConfig)


def __getattr__(name: str) -> Any:  # PEP 562: KitConfig's class is made when first used
    if name == "KitConfig":
        from ._kit_config import KitConfig

        globals()[name] = KitConfig
        return KitConfig
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted({*globals(), *__all__})


class _DefaultCamera:
    """Marks a kit's camera as the default one, not made yet."""


_DEFAULT_CAMERA: Final = _DefaultCamera()


def _serial(prefix: str, index: int, count: int) -> str:
    width = len(str(count - 1))
    return f"{prefix}{index:0{width}d}"


_current: SimulatedKit | None = None


def use_kit(
    kit: KitConfig | KitDefinition | SimulatedKit | str | None = None,
    *,
    time_scale: float | None = None,
    wired: bool | None = None,
) -> SimulatedKit:
    """Make a fresh kit the current one, and return it.

    The simulated environment finds this kit's boards from now on. Boards found before
    keep talking to the simulators they were found on.

    :param kit: the new kit: a configuration, a registry kit or a kit's name
        (``"sr2019"``), or a kit already made; the default kit if omitted.
    :param time_scale: the time scale of a named kit (see :class:`SimulatedKit`).
    :param wired: when to feed the boards from the power board's outputs (see
        :class:`SimulatedKit`); not for a kit already made.
    :raises TypeError: ``kit`` is none of those.
    :raises ValueError: there is no kit of that name; the message lists the kits.
    """
    global _current
    if kit is None or _is_kit_config(kit) or isinstance(kit, KitDefinition | str):
        kit = SimulatedKit(kit, time_scale=time_scale, wired=wired)
    elif not isinstance(kit, SimulatedKit):
        raise TypeError(
            "use_kit takes a KitConfig, a KitDefinition, a kit's name or a SimulatedKit, "
            f"not {type(kit).__name__}"
        )
    _current = kit
    return kit


def kit_from_environment() -> str:
    """The kit named by ``J5AIO_KIT``, or the default kit's name when it is unset.

    :raises ValueError: ``J5AIO_KIT`` names no kit; the message lists the kits.
    """
    name = os.environ.get(KIT_VARIABLE, "").strip()
    if not name:
        return DEFAULT_KIT
    try:
        return get_kit(name).name
    except ValueError as error:
        raise ValueError(f"{KIT_VARIABLE}={name!r}: {error}") from None


def current_kit() -> SimulatedKit:
    """Return the kit in use, making it on first use.

    That is the kit of the file ``J5AIO_KIT_FILE`` names (:mod:`j5aio.simulator.kit_file`),
    else the ``J5AIO_KIT`` kit, else the default kit; it is wired from the start, as
    the robot is (see :class:`SimulatedKit`).

    :raises ValueError: ``J5AIO_KIT`` names no kit (the message lists the kits), or the
        kit file cannot be used (the message says why).
    """
    if _current is None:
        if os.environ.get(_KIT_FILE_VARIABLE, "").strip():
            from .kit_file import KIT_FILE_VARIABLE, kit_file_from_environment, time_scale_of

            from_file = kit_file_from_environment()
            if from_file is not None:
                scale = time_scale_of(os.environ[KIT_FILE_VARIABLE].strip())
                return use_kit(from_file, time_scale=scale, wired=True)
        return use_kit(kit_from_environment(), wired=True)
    return _current

"""The simulated kit: which board simulators exist, and which kit is in use now.

A :class:`KitConfig` says how many of each board the kit has; a :class:`SimulatedKit`
holds one simulator per board, each with its own serial number, so that a program or a
test can look at what the boards are doing::

    kit = use_kit(KitConfig(motor_boards=1))
    ...  # run a robot on the simulated environment
    kit.motor_boards[0].motors[0].mode      # MotorMode.BRAKE

The simulated environment (:mod:`j5aio.simulator.environment`) finds the boards of the
kit returned by :func:`current_kit`. Without a call to :func:`use_kit` that is the
default kit: one power board, two motor boards, one servo board and one SourceBots
Arduino.

Simulators are plain state machines: read their state from the thread that runs the
event loop, between awaits.
"""

from __future__ import annotations

import itertools
from collections.abc import Iterator
from dataclasses import dataclass, fields
from typing import TYPE_CHECKING, Final

from .arena import SimulatedWorld
from .base import SerialBoardSimulator, UsbBoardSimulator
from .sb_arduino_2019 import SBArduinoSimulator
from .sr_motor_fw3 import SRMotorBoardFw3Simulator
from .sr_power_fw3 import SRPowerBoardFw3Simulator
from .sr_ruggeduino_fw1 import SRRuggeduinoSimulator
from .sr_servo_fw2 import SRServoBoardFw2Simulator

if TYPE_CHECKING:
    from .camera import SimulatedCamera

__all__ = ["KitConfig", "SimulatedKit", "current_kit", "use_kit"]

#: The most boards of one kind a simulated kit may have.
MAX_BOARDS_OF_A_KIND: Final = 99

_kit_numbers = itertools.count(1)


@dataclass(frozen=True)
class KitConfig:
    """How many of each board the simulated kit has, and how fast its time runs.

    :param power_boards: SR v4 power boards (firmware 3, USB).
    :param motor_boards: SR v4 motor boards (firmware 3, serial).
    :param servo_boards: SR v4 servo boards (firmware 2, USB).
    :param sb_arduinos: SourceBots Arduinos (2019 firmware, serial).
    :param ruggeduinos: SR Ruggeduinos (firmware 1, serial).
    :param time_scale: multiplies the time a board takes to boot when its port opens (an
        Arduino's 1.5 s): ``1.0`` is as slow as the real boards, ``0`` (the default)
        instant. Other time (a piezo note playing) passes at the real rate.
    :raises TypeError: a count is not an int, or ``time_scale`` not a number.
    :raises ValueError: a count is outside 0 to 99, or ``time_scale`` is negative.
    """

    power_boards: int = 1
    motor_boards: int = 2
    servo_boards: int = 1
    sb_arduinos: int = 1
    ruggeduinos: int = 0
    time_scale: float = 0.0

    def __post_init__(self) -> None:
        for field in fields(self):
            value = getattr(self, field.name)
            if field.name == "time_scale":
                if isinstance(value, bool) or not isinstance(value, int | float):
                    raise TypeError(f"time_scale must be a number, not {type(value).__name__}")
                if not value >= 0:
                    raise ValueError(f"time_scale must be 0 or more, not {value}")
                continue
            if isinstance(value, bool) or not isinstance(value, int):
                raise TypeError(f"{field.name} must be an int, not {type(value).__name__}")
            if not 0 <= value <= MAX_BOARDS_OF_A_KIND:
                raise ValueError(
                    f"{field.name} must be between 0 and {MAX_BOARDS_OF_A_KIND}, not {value}"
                )


class SimulatedKit:
    """One simulator for each board of a :class:`KitConfig`.

    Serial numbers are distinct and sort in board order, so that ``kit.motor_boards[i]``
    is the board a robot sees as ``robot.motor_boards[i]``: ``SIMPB0`` for the first power
    board, ``SIMMB0`` and ``SIMMB1`` for motor boards, ``SIMSB0`` for a servo board,
    ``SIMSBA0`` for a SourceBots Arduino and ``SIMRD0`` for a Ruggeduino (``SIMMB00`` to
    ``SIMMB11`` in a kit of twelve motor boards).

    :param config: the boards to make; the default kit if omitted.
    """

    def __init__(self, config: KitConfig | None = None) -> None:
        self._config = config if config is not None else KitConfig()
        self._name = f"kit{next(_kit_numbers)}"
        #: The arena, the robot's pose and its drive (see :mod:`j5aio.simulator.arena`).
        self.world = SimulatedWorld()
        #: The robot's camera (a :class:`~j5aio.simulator.camera.SimulatedCamera`), or
        #: ``None`` for a robot without one.
        self.camera: SimulatedCamera | None = _default_camera()
        c = self._config
        self._power_boards = tuple(
            SRPowerBoardFw3Simulator(_serial("SIMPB", i, c.power_boards))
            for i in range(c.power_boards)
        )
        self._motor_boards = tuple(
            SRMotorBoardFw3Simulator(_serial("SIMMB", i, c.motor_boards))
            for i in range(c.motor_boards)
        )
        self._servo_boards = tuple(
            SRServoBoardFw2Simulator(_serial("SIMSB", i, c.servo_boards))
            for i in range(c.servo_boards)
        )
        self._sb_arduinos = tuple(
            SBArduinoSimulator(_serial("SIMSBA", i, c.sb_arduinos)) for i in range(c.sb_arduinos)
        )
        self._ruggeduinos = tuple(
            SRRuggeduinoSimulator(_serial("SIMRD", i, c.ruggeduinos)) for i in range(c.ruggeduinos)
        )

    @property
    def config(self) -> KitConfig:
        """The configuration this kit was made from."""
        return self._config

    @property
    def name(self) -> str:
        """A name unique to this kit in the program (``kit1``, ``kit2``...), used in port names."""
        return self._name

    @property
    def time_scale(self) -> float:
        """The factor applied to every simulated delay."""
        return self._config.time_scale

    @property
    def power_boards(self) -> tuple[SRPowerBoardFw3Simulator, ...]:
        """The simulated power boards."""
        return self._power_boards

    @property
    def motor_boards(self) -> tuple[SRMotorBoardFw3Simulator, ...]:
        """The simulated motor boards."""
        return self._motor_boards

    @property
    def servo_boards(self) -> tuple[SRServoBoardFw2Simulator, ...]:
        """The simulated servo boards."""
        return self._servo_boards

    @property
    def sb_arduinos(self) -> tuple[SBArduinoSimulator, ...]:
        """The simulated SourceBots Arduinos."""
        return self._sb_arduinos

    @property
    def ruggeduinos(self) -> tuple[SRRuggeduinoSimulator, ...]:
        """The simulated Ruggeduinos."""
        return self._ruggeduinos

    def serial_simulators(self) -> tuple[SerialBoardSimulator, ...]:
        """Every board reached through a serial port."""
        return (*self._motor_boards, *self._sb_arduinos, *self._ruggeduinos)

    def usb_simulators(self) -> tuple[UsbBoardSimulator, ...]:
        """Every board reached through USB control transfers."""
        return (*self._power_boards, *self._servo_boards)

    def __iter__(self) -> Iterator[SerialBoardSimulator | UsbBoardSimulator]:
        """Iterate over every board of the kit."""
        yield from self.usb_simulators()
        yield from self.serial_simulators()

    def __len__(self) -> int:
        """How many boards the kit has."""
        return len(self.usb_simulators()) + len(self.serial_simulators())

    def __repr__(self) -> str:
        return f"<SimulatedKit {self._name} {self._config!r}>"


def _default_camera() -> SimulatedCamera:
    from .camera import SimulatedCamera

    return SimulatedCamera()


def _serial(prefix: str, index: int, count: int) -> str:
    width = len(str(count - 1))
    return f"{prefix}{index:0{width}d}"


_current: SimulatedKit | None = None


def use_kit(kit: KitConfig | SimulatedKit | None = None) -> SimulatedKit:
    """Make a fresh kit the current one, and return it.

    The simulated environment finds this kit's boards from now on. Boards found before
    keep talking to the simulators they were found on.

    :param kit: the configuration of the new kit (the default kit if omitted), or a kit
        already made.
    :raises TypeError: ``kit`` is neither a :class:`KitConfig` nor a :class:`SimulatedKit`.
    """
    global _current
    if kit is None or isinstance(kit, KitConfig):
        kit = SimulatedKit(kit)
    elif not isinstance(kit, SimulatedKit):
        raise TypeError(f"use_kit takes a KitConfig or a SimulatedKit, not {type(kit).__name__}")
    _current = kit
    return kit


def current_kit() -> SimulatedKit:
    """Return the kit in use, making the default kit on first use."""
    if _current is None:
        return use_kit()
    return _current

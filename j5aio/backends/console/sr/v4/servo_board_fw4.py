"""Console backends of the SR v4 Servo Board with the serial firmware (4.3 and SB's 4.4)."""

from __future__ import annotations

from typing import ClassVar

from j5aio.backends.console.backend import ConsoleBackend
from j5aio.backends.console.console import Console
from j5aio.backends.hardware.sr.v4.servo_fw4_codec import SB_DEFAULT_PULSE_LIMITS
from j5aio.boards.sb.servo_board import SBServoBoard
from j5aio.boards.sr.v4.servo_board_fw4 import ServoBoardFw4
from j5aio.components.flag import FlagInterface
from j5aio.components.pulse_servo import (
    DEFAULT_PULSE_LIMITS,
    PulseLimits,
    PulseServoInterface,
    position_for_pulse,
    pulse_for_position,
)
from j5aio.components.servo import ServoPosition
from j5aio.components.supply_sensor import SupplySensorInterface

__all__ = ["SBServoBoardConsoleBackend", "SRV4ServoBoardFw4ConsoleBackend"]

_TICK_US = 5
_FLAG_NAMES = ("Power good", "Watchdog failed")


class SRV4ServoBoardFw4ConsoleBackend(
    PulseServoInterface, SupplySensorInterface, FlagInterface, ConsoleBackend,
):
    """The serial-firmware Servo Board on the console: prints every servo move.

    Every servo starts unpowered. Pulses are computed as the board would (5 µs steps),
    so positions read back as they would on the board; readings are asked for.

    :param serial: the board's serial number.
    :param console_class: the console to talk through.
    """

    board = ServoBoardFw4

    #: The shortest pulse the firmware accepts, in µs.
    MIN_PULSE: ClassVar[int] = 500
    #: The longest pulse the firmware accepts, in µs.
    MAX_PULSE: ClassVar[int] = 4000
    #: The pulses positions -1 and 1 give until a program sets its own, in µs.
    DEFAULT_LIMITS: ClassVar[PulseLimits] = DEFAULT_PULSE_LIMITS

    def __init__(self, serial: str, console_class: type[Console] | None = None) -> None:
        super().__init__(serial, console_class)
        self._servos = range(self.board.SERVO_COUNT)
        self._limits: list[PulseLimits] = [self.DEFAULT_LIMITS for _ in self._servos]
        self._pulses: list[int | None] = [None for _ in self._servos]

    async def get_servo_pulse_range(self, identifier: int) -> PulseLimits:
        """Return the firmware's shortest and longest pulse, in µs."""
        self._check_identifier("servo", identifier, self._servos)
        return (self.MIN_PULSE, self.MAX_PULSE)

    async def get_servo_pulse_limits(self, identifier: int) -> PulseLimits:
        """Return the pulses positions -1 and 1 give, in µs."""
        self._check_identifier("servo", identifier, self._servos)
        return self._limits[identifier]

    async def set_servo_pulse_limits(self, identifier: int, limits: PulseLimits) -> None:
        """Remember the pulses positions -1 and 1 give, and say so."""
        self._check_identifier("servo", identifier, self._servos)
        lower, upper = limits
        if not self.MIN_PULSE <= lower < upper <= self.MAX_PULSE:
            raise ValueError(
                f"pulse limits must be within {self.MIN_PULSE} to {self.MAX_PULSE} µs, lower "
                f"first; got {lower} to {upper} µs",
            )
        self._limits[identifier] = (lower, upper)
        await self._console.info(f"Servo {identifier} now spans {lower} to {upper} µs.")

    async def get_servo_pulse_width(self, identifier: int) -> int | None:
        """Return the pulse servo ``identifier`` was last given, in µs (``None``: unpowered)."""
        self._check_identifier("servo", identifier, self._servos)
        return self._pulses[identifier]

    async def get_servo_position(self, identifier: int) -> ServoPosition:
        """Return the position of the last pulse (``None``: unpowered)."""
        pulse = await self.get_servo_pulse_width(identifier)
        if pulse is None:
            return None
        return position_for_pulse(pulse, self._limits[identifier])

    async def set_servo_position(self, identifier: int, position: ServoPosition) -> None:
        """Print the servo's new position and pulse."""
        self._check_identifier("servo", identifier, self._servos)
        if position is None:
            self._pulses[identifier] = None
            await self._console.info(f"Setting servo {identifier} to unpowered.")
            return
        pulse = pulse_for_position(position, self._limits[identifier])
        self._pulses[identifier] = pulse - pulse % _TICK_US
        await self._console.info(f"Setting servo {identifier} to {position} ({pulse} µs).")

    async def get_supply_voltage(self, identifier: int) -> float:
        """Ask for the servo rail's voltage."""
        self._check_identifier("supply sensor", identifier, range(1))
        return await self._console.read("Servo supply voltage [volts]", float)

    async def get_supply_current(self, identifier: int) -> float:
        """Ask for the servo rail's current."""
        self._check_identifier("supply sensor", identifier, range(1))
        return await self._console.read("Servo supply current [amps]", float)

    async def get_flag_state(self, identifier: int) -> bool:
        """Ask whether flag 0 (power good) or 1 (watchdog failed) is raised."""
        self._check_identifier("flag", identifier, range(len(_FLAG_NAMES)))
        return await self._console.read(f"{_FLAG_NAMES[identifier]} [true/false]", bool)


class SBServoBoardConsoleBackend(SRV4ServoBoardFw4ConsoleBackend):
    """The SourceBots servo board (firmware 4.4, 8 servos) on the console."""

    board = SBServoBoard
    MIN_PULSE: ClassVar[int] = 300
    DEFAULT_LIMITS: ClassVar[PulseLimits] = SB_DEFAULT_PULSE_LIMITS

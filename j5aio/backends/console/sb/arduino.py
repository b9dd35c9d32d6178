"""The console backend of the SourceBots Arduino."""

from __future__ import annotations

from datetime import timedelta
from typing import ClassVar

from j5aio.backends.console.arduino import ArduinoConsoleBackend
from j5aio.backends.console.console import Console
from j5aio.boards.sb.arduino import SBArduinoBoard
from j5aio.components.derived.ultrasound import UltrasoundInterface
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.components.servo import ServoInterface, ServoPosition

__all__ = ["SBArduinoConsoleBackend"]


class SBArduinoConsoleBackend(ServoInterface, UltrasoundInterface, ArduinoConsoleBackend):
    """The SourceBots Arduino on the console: pins, servos and ultrasound readings.

    :param serial: the board's serial number.
    :param console_class: the console to talk through.
    """

    board = SBArduinoBoard

    _SERVOS: ClassVar[range] = range(SBArduinoBoard.SERVO_COUNT)

    def __init__(self, serial: str, console_class: type[Console] | None = None) -> None:
        super().__init__(serial, console_class)
        self._servo_positions: list[ServoPosition] = [None for _ in self._SERVOS]

    async def get_servo_position(self, identifier: int) -> ServoPosition:
        """Return where servo ``identifier`` was last sent (``None``: unpowered)."""
        self._check_identifier("servo", identifier, self._SERVOS)
        return self._servo_positions[identifier]

    async def set_servo_position(self, identifier: int, position: ServoPosition) -> None:
        """Print the new position of servo ``identifier``."""
        self._check_identifier("servo", identifier, self._SERVOS)
        await self._console.info(f"Set servo {identifier} to {position}")
        self._servo_positions[identifier] = position

    async def get_ultrasound_pulse(
        self, trigger_pin_identifier: int, echo_pin_identifier: int,
    ) -> timedelta | None:
        """Ask how long the echo took, in microseconds; an answer of 0 means no echo."""
        self._check_ultrasound_pins(trigger_pin_identifier, echo_pin_identifier)
        microseconds = await self._console.read(
            f"Response time for ultrasound sensor on pins "
            f"{trigger_pin_identifier}/{echo_pin_identifier} [microseconds]",
            float,
        )
        self._ultrasound_used(trigger_pin_identifier, echo_pin_identifier)
        # As on the board itself, a reading of 0 says that no echo came back.
        return timedelta(microseconds=microseconds) if microseconds else None

    async def get_ultrasound_distance(
        self, trigger_pin_identifier: int, echo_pin_identifier: int,
    ) -> float | None:
        """Ask for the distance to the nearest object, in metres; 0 means no echo."""
        self._check_ultrasound_pins(trigger_pin_identifier, echo_pin_identifier)
        metres = await self._console.read(
            f"Distance for ultrasound sensor on pins "
            f"{trigger_pin_identifier}/{echo_pin_identifier} [metres]",
            float,
        )
        self._ultrasound_used(trigger_pin_identifier, echo_pin_identifier)
        return metres or None

    def _check_ultrasound_pins(self, trigger: int, echo: int) -> None:
        for identifier in (trigger, echo):
            self._pin(identifier)

    def _ultrasound_used(self, trigger: int, echo: int) -> None:
        """Record the modes the firmware leaves the pins in after a measurement."""
        self._pins[trigger].mode = GPIOPinMode.DIGITAL_OUTPUT
        self._pins[trigger].digital_state = False
        self._pins[echo].mode = GPIOPinMode.DIGITAL_INPUT

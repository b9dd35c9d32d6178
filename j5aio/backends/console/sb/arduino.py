"""The console backend of the SourceBots Arduino."""

from __future__ import annotations

from typing import ClassVar

from j5aio.backends.console.arduino_ultrasound import ArduinoUltrasoundConsoleBackend
from j5aio.backends.console.console import Console
from j5aio.boards.sb.arduino import SBArduinoBoard
from j5aio.components.servo import ServoInterface, ServoPosition

__all__ = ["SBArduinoConsoleBackend"]


class SBArduinoConsoleBackend(ServoInterface, ArduinoUltrasoundConsoleBackend):
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

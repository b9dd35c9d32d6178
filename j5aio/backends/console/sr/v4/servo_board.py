"""The console backend of the Student Robotics v4 Servo Board."""

from __future__ import annotations

from typing import ClassVar

from j5aio.backends.console.backend import ConsoleBackend
from j5aio.backends.console.console import Console
from j5aio.boards.sr.v4.servo_board import ServoBoard
from j5aio.components.servo import ServoInterface, ServoPosition

__all__ = ["SRV4ServoBoardConsoleBackend"]


class SRV4ServoBoardConsoleBackend(ServoInterface, ConsoleBackend):
    """The Servo Board on the console: prints every move of a servo.

    Every servo starts unpowered.

    :param serial: the board's serial number.
    :param console_class: the console to talk through.
    """

    board = ServoBoard

    _SERVOS: ClassVar[range] = range(ServoBoard.SERVO_COUNT)

    def __init__(self, serial: str, console_class: type[Console] | None = None) -> None:
        super().__init__(serial, console_class)
        self._positions: list[ServoPosition] = [None for _ in self._SERVOS]

    async def get_servo_position(self, identifier: int) -> ServoPosition:
        """Return where servo ``identifier`` was last sent (``None``: unpowered)."""
        self._check_identifier("servo", identifier, self._SERVOS)
        return self._positions[identifier]

    async def set_servo_position(self, identifier: int, position: ServoPosition) -> None:
        """Print the new position of servo ``identifier``."""
        self._check_identifier("servo", identifier, self._SERVOS)
        shown = "unpowered" if position is None else str(position)
        await self._console.info(f"Setting servo {identifier} to {shown}.")
        self._positions[identifier] = position

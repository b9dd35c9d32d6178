"""The console backend of the Student Robotics v4 Motor Board."""

from __future__ import annotations

from typing import ClassVar

from j5aio.backends.console.backend import ConsoleBackend
from j5aio.backends.console.console import Console
from j5aio.boards.sr.v4.motor_board import MotorBoard
from j5aio.components.motor import MotorInterface, MotorSpecialState, MotorState

__all__ = ["SRV4MotorBoardConsoleBackend"]


class SRV4MotorBoardConsoleBackend(MotorInterface, ConsoleBackend):
    """The Motor Board on the console: prints every change of a motor.

    Both motors start braked, as the real board does.

    :param serial: the board's serial number.
    :param console_class: the console to talk through.
    """

    board = MotorBoard

    _MOTORS: ClassVar[range] = range(MotorBoard.MOTOR_COUNT)

    def __init__(self, serial: str, console_class: type[Console] | None = None) -> None:
        super().__init__(serial, console_class)
        self._states: list[MotorState] = [MotorSpecialState.BRAKE for _ in self._MOTORS]

    async def get_motor_state(self, identifier: int) -> MotorState:
        """Return what motor ``identifier`` was last set to."""
        self._check_identifier("motor", identifier, self._MOTORS)
        return self._states[identifier]

    async def set_motor_state(self, identifier: int, power: MotorState) -> None:
        """Print the new state of motor ``identifier``."""
        self._check_identifier("motor", identifier, self._MOTORS)
        shown = power.name if isinstance(power, MotorSpecialState) else str(power)
        await self._console.info(f"Setting motor {identifier} to {shown}.")
        self._states[identifier] = power

"""The console backend of the Student Robotics v4 Motor Board."""

from __future__ import annotations

from typing import ClassVar

from j5aio.backends.console.backend import ConsoleBackend
from j5aio.backends.console.console import Console
from j5aio.boards.sr.v4.motor_board import MotorBoard
from j5aio.components.motor import MotorInterface, MotorSpecialState, MotorState

__all__ = ["SRV4MotorBoardConsoleBackend"]


class SRV4MotorBoardConsoleBackend(MotorInterface, ConsoleBackend):
    """The Motor Board on the console: prints every change of a motor, with the duty driven.

    Both motors start braked, as the real board does. The duty shown is the one the
    firmware 3 board drives for the power j5aio sends, ``round(p x 100)`` percent.

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

    @staticmethod
    def describe_drive(power: MotorState) -> str:
        """Say what the board does for ``power``, e.g. ``forward at 50% duty``."""
        if isinstance(power, MotorSpecialState):
            return "brake" if power is MotorSpecialState.BRAKE else "coast"
        percent = round(power * 100)
        direction = "forward" if percent >= 0 else "reverse"
        return f"{direction} at {abs(percent)}% duty"

    async def set_motor_state(self, identifier: int, power: MotorState) -> None:
        """Print the new state of motor ``identifier``, then the duty the board drives."""
        self._check_identifier("motor", identifier, self._MOTORS)
        shown = power.name if isinstance(power, MotorSpecialState) else str(power)
        await self._console.info(f"Setting motor {identifier} to {shown}.")
        if not isinstance(power, MotorSpecialState):
            drive = self.describe_drive(power)
            await self._console.info(f"Motor {identifier}: {drive}.")
        self._states[identifier] = power

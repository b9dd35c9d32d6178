"""The Bee Board as students see it: two motors, an LED and a button."""

from __future__ import annotations

from typing import TYPE_CHECKING, ClassVar

from j5aio.boards.board import Board
from j5aio.components.button import Button
from j5aio.components.led import LED
from j5aio.components.motor import Motor

if TYPE_CHECKING:
    from j5aio.backends.backend import Backend
    from j5aio.components.component import Component

__all__ = ["BeeBoard"]


class BeeBoard(Board):
    """The Bee Board: motors 0 and 1, one LED and one button.

    :param serial_number: the board's serial number.
    :param backend: the backend that drives it.
    """

    name: ClassVar[str] = "Bee Board"

    #: How many motors the board has.
    MOTOR_COUNT: ClassVar[int] = 2

    def __init__(self, serial_number: str, backend: Backend) -> None:
        super().__init__(serial_number, backend)
        self._motors = tuple(Motor(i, backend) for i in range(self.MOTOR_COUNT))
        self._led = LED(0, backend)
        self._button = Button(0, backend)

    @property
    def motors(self) -> tuple[Motor, ...]:
        """The motors, numbered 0 and 1."""
        return self._motors

    @property
    def led(self) -> LED:
        """The LED."""
        return self._led

    @property
    def button(self) -> Button:
        """The button."""
        return self._button

    @staticmethod
    def supported_components() -> set[type[Component]]:
        """The components of the board: a backend must implement their interfaces."""
        return {Motor, LED, Button}

    async def _setup(self) -> None:
        """Start with the motors stopped and the LED dark."""
        await self.make_safe()

    async def make_safe(self) -> None:
        """Stop both motors (the board has no brake) and darken the LED."""
        for motor in self._motors:
            await motor.set_power(0.0)
        await self._led.set_state(False)

"""The Blinkenboard: four LEDs and a button, as a student sees it."""

from __future__ import annotations

from typing import TYPE_CHECKING, ClassVar, cast

from j5aio.boards.board import Board
from j5aio.components.button import Button, ButtonInterface
from j5aio.components.led import LED, LEDInterface

if TYPE_CHECKING:
    from j5aio.backends.backend import Backend
    from j5aio.components.component import Component


class BlinkenBoard(Board):
    """An imaginary board with four LEDs (0 to 3) and one button."""

    name: ClassVar[str] = "Blinkenboard"

    #: How many LEDs the board has.
    LED_COUNT: ClassVar[int] = 4

    def __init__(self, serial_number: str, backend: Backend) -> None:
        super().__init__(serial_number, backend)
        self._leds = tuple(
            LED(i, cast(LEDInterface, backend)) for i in range(self.LED_COUNT)
        )
        self._button = Button(0, cast(ButtonInterface, backend))

    @property
    def leds(self) -> tuple[LED, ...]:
        """The LEDs, numbered 0 to 3."""
        return self._leds

    @property
    def button(self) -> Button:
        """The button."""
        return self._button

    @staticmethod
    def supported_components() -> set[type[Component]]:
        """The components of the board: a backend must implement their interfaces."""
        return {LED, Button}

    async def _setup(self) -> None:
        """Start with every LED dark."""
        await self.make_safe()

    async def make_safe(self) -> None:
        """Darken every LED."""
        for led in self._leds:
            await led.set_state(False)

"""The Blinken board: four LEDs."""

from __future__ import annotations

from typing import TYPE_CHECKING, ClassVar, cast

from j5aio.boards.board import Board
from j5aio.components.led import LED, LEDInterface

if TYPE_CHECKING:
    from j5aio.backends.backend import Backend
    from j5aio.components.component import Component

__all__ = ["BlinkenBoard"]


class BlinkenBoard(Board):
    """A board with four LEDs, numbered 0 to 3."""

    name: ClassVar[str] = "Blinken Board"
    LED_COUNT: ClassVar[int] = 4

    def __init__(self, serial_number: str, backend: Backend) -> None:
        super().__init__(serial_number, backend)
        led_backend = cast(LEDInterface, backend)
        self._leds = tuple(LED(i, led_backend) for i in range(self.LED_COUNT))

    @property
    def leds(self) -> tuple[LED, ...]:
        """The LEDs."""
        return self._leds

    @staticmethod
    def supported_components() -> set[type[Component]]:
        """The component classes on the board."""
        return {LED}

    async def make_safe(self) -> None:
        """Turn every LED off."""
        for led in self._leds:
            await led.set_state(False)

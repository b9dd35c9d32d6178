"""The KCH: Student Robotics' Raspberry Pi HAT, with three user RGB LEDs and the start LED."""

from __future__ import annotations

from typing import TYPE_CHECKING, ClassVar

from j5aio.boards.board import Board
from j5aio.components.flashing_led import FlashingLED
from j5aio.components.rgb_led import RGBLED, RGBColour
from j5aio.numbered import NumberedComponents

if TYPE_CHECKING:
    from j5aio.backends.backend import Backend
    from j5aio.components.component import Component

__all__ = ["Colour", "KCHBoard"]


class Colour:
    """The eight colours a KCH LED can show (each channel is on or off)."""

    OFF: ClassVar[RGBColour] = (0.0, 0.0, 0.0)
    RED: ClassVar[RGBColour] = (1.0, 0.0, 0.0)
    YELLOW: ClassVar[RGBColour] = (1.0, 1.0, 0.0)
    GREEN: ClassVar[RGBColour] = (0.0, 1.0, 0.0)
    CYAN: ClassVar[RGBColour] = (0.0, 1.0, 1.0)
    BLUE: ClassVar[RGBColour] = (0.0, 0.0, 1.0)
    MAGENTA: ClassVar[RGBColour] = (1.0, 0.0, 1.0)
    WHITE: ClassVar[RGBColour] = (1.0, 1.0, 1.0)


class KCHBoard(Board):
    """The KCH, the HAT on the Raspberry Pi of the Student Robotics 2023+ kit.

    Its three user LEDs A, B and C (:attr:`leds`, 0 to 2) each have a red, a green and a
    blue part that are on or off, so they show the eight :class:`Colour` s: any
    brightness above 0 lights a part fully. Its start LED (:attr:`start_led`) flashes
    while a robot waits for the start button. Colours stay lit while the program runs,
    also once it is made safe; when the program ends, closing the board releases the
    GPIO pins and every LED goes dark (sr-robot3, which leaves its user LED pins driven
    at exit, keeps them lit).

    :param serial_number: the KCH's asset code.
    :param backend: the backend that drives the LEDs.
    """

    name: ClassVar[str] = "Student Robotics KCH"

    #: The number of user RGB LEDs (A, B and C).
    LED_COUNT: ClassVar[int] = 3

    def __init__(self, serial_number: str, backend: Backend) -> None:
        super().__init__(serial_number, backend)
        self._leds = NumberedComponents(
            (RGBLED(i, backend) for i in range(self.LED_COUNT)), owner=self, kind="LED",
        )
        self._start_led = FlashingLED(0, backend)

    @property
    def leds(self) -> tuple[RGBLED, ...]:
        """The user LEDs A, B and C (0, 1 and 2)."""
        return self._leds

    @property
    def start_led(self) -> FlashingLED:
        """The start LED, which flashes while the robot waits to be started."""
        return self._start_led

    @staticmethod
    def supported_components() -> set[type[Component]]:
        """The component classes on a KCH."""
        return {RGBLED, FlashingLED}

    async def make_safe(self) -> None:
        """Turn the start LED off; the user LEDs keep their colours until the board closes."""
        await self._start_led.set_state(False)

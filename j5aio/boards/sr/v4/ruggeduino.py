"""The Student Robotics Ruggeduino: an Arduino Uno that also takes raw string commands."""

from __future__ import annotations

from typing import TYPE_CHECKING, ClassVar

from j5aio.boards.arduino.uno import ArduinoUno
from j5aio.components.gpio_pin import GPIOPin, GPIOPinMode
from j5aio.components.led import LED

if TYPE_CHECKING:
    from j5aio.backends.backend import Backend
    from j5aio.components.component import Component
    from j5aio.components.string_command import StringCommandComponent

__all__ = ["Ruggeduino"]


class Ruggeduino(ArduinoUno):
    """The Student Robotics Ruggeduino.

    It has the pins of an Arduino Uno, plus :attr:`command` to send a firmware of the
    team's own a raw text command.

    :param serial_number: the board's serial number.
    :param backend: the backend that drives the board.
    """

    name: ClassVar[str] = "Ruggeduino"

    #: Firmware 1 drives A0 to A5 (pins 14 to 19) as digital pins too, as the Uno can.
    ANALOGUE_PIN_MODES: ClassVar[frozenset[GPIOPinMode]] = ArduinoUno.DIGITAL_PIN_MODES | {
        GPIOPinMode.ANALOGUE_INPUT,
    }

    def __init__(self, serial_number: str, backend: Backend) -> None:
        # (imported here: a program on a kit without a Ruggeduino loads none of it)
        from j5aio.components.string_command import StringCommandComponent

        super().__init__(serial_number, backend)
        self._command = StringCommandComponent(
            0,
            backend,
        )

    @property
    def command(self) -> StringCommandComponent:
        """Sends raw text commands to the board's firmware."""
        return self._command

    @staticmethod
    def supported_components() -> set[type[Component]]:
        """The component classes on a Ruggeduino."""
        from j5aio.components.string_command import StringCommandComponent

        return {GPIOPin, LED, StringCommandComponent}

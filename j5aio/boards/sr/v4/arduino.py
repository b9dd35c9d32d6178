"""The SR Arduino of the 2023+ kit (firmware 2): a Ruggeduino whose pins are all digital, plus ultrasound."""  # noqa: E501

from __future__ import annotations

from typing import TYPE_CHECKING, ClassVar

from j5aio.boards.arduino.all_digital import AllDigitalUno
from j5aio.boards.sr.v4.ruggeduino import Ruggeduino
from j5aio.components.derived.ultrasound import UltrasoundSensor
from j5aio.components.gpio_pin import GPIOPin
from j5aio.components.led import LED
from j5aio.components.string_command import StringCommandComponent

if TYPE_CHECKING:
    from j5aio.components.component import Component

__all__ = ["SRArduinoBoard"]


class SRArduinoBoard(AllDigitalUno, Ruggeduino):
    """The Student Robotics Arduino (an Uno running SR firmware 2, ``SRduino:2``).

    It speaks the Ruggeduino's single-character protocol. Every pin from 2 to 19 is a
    digital input, input with pull-up or output; A0 to A5 (14 to 19) also read voltages.
    An ultrasound sensor works on any two pins: ``board.ultrasound_sensors[trigger,
    echo]``, whose ``distance()`` is ``None`` when no echo comes back.
    :attr:`~j5aio.boards.sr.v4.ruggeduino.Ruggeduino.command` sends raw text, as
    sr-robot3's ``command()`` does.

    :param serial_number: the board's serial number.
    :param backend: the backend that drives the board.
    """

    name: ClassVar[str] = "SR Arduino"

    @staticmethod
    def supported_components() -> set[type[Component]]:
        """The component classes on an SR Arduino."""
        return {GPIOPin, LED, StringCommandComponent, UltrasoundSensor}

"""The SR Arduino of the 2023+ kit (firmware 2): a Ruggeduino whose pins are all digital, plus ultrasound."""  # noqa: E501

from __future__ import annotations

from typing import TYPE_CHECKING, ClassVar

from j5aio.boards.arduino.uno import ArduinoUno
from j5aio.boards.sb.arduino import UltrasoundSensors
from j5aio.boards.sr.v4.ruggeduino import Ruggeduino
from j5aio.components.derived.ultrasound import UltrasoundSensor
from j5aio.components.gpio_pin import GPIOPin, GPIOPinMode
from j5aio.components.led import LED
from j5aio.components.string_command import StringCommandComponent

if TYPE_CHECKING:
    from j5aio.backends.backend import Backend
    from j5aio.components.component import Component
    from j5aio.components.gpio_pin import FirmwareMode

__all__ = ["SRArduinoBoard"]


class SRArduinoBoard(Ruggeduino):
    """The Student Robotics Arduino (an Uno running SR firmware 2, ``SRduino:2``).

    It speaks the Ruggeduino's single-character protocol. Every pin from 2 to 19 is a
    digital input, input with pull-up or output; A0 to A5 (14 to 19) also read voltages.
    An ultrasound sensor works on any two pins: ``board.ultrasound_sensors[trigger,
    echo]``, whose ``distance()`` is ``None`` when no echo comes back. :attr:`command`
    sends raw text, as sr-robot3's ``command()`` does.

    :param serial_number: the board's serial number.
    :param backend: the backend that drives the board.
    """

    name: ClassVar[str] = "SR Arduino"

    ANALOGUE_PIN_MODES: ClassVar[frozenset[GPIOPinMode]] = ArduinoUno.DIGITAL_PIN_MODES | {
        GPIOPinMode.ANALOGUE_INPUT,
    }
    DIGITAL_PIN_FIRMWARE_MODES: ClassVar[frozenset[FirmwareMode]] = frozenset(
        {UltrasoundSensor},
    )
    ANALOGUE_PIN_FIRMWARE_MODES: ClassVar[frozenset[FirmwareMode]] = frozenset(
        {UltrasoundSensor},
    )

    def __init__(self, serial_number: str, backend: Backend) -> None:
        super().__init__(serial_number, backend)
        self._ultrasound_sensors = UltrasoundSensors(self)

    @property
    def ultrasound_sensors(self) -> UltrasoundSensors:
        """Ultrasound sensors on demand: ``board.ultrasound_sensors[trigger_pin, echo_pin]``."""
        return self._ultrasound_sensors

    @staticmethod
    def supported_components() -> set[type[Component]]:
        """The component classes on an SR Arduino."""
        return {GPIOPin, LED, StringCommandComponent, UltrasoundSensor}

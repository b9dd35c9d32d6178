"""An Arduino Uno whose firmware makes every pin digital and times ultrasound on any two pins."""

from __future__ import annotations

from typing import TYPE_CHECKING, ClassVar

from j5aio.boards.arduino.ultrasound import UltrasoundSensors
from j5aio.boards.arduino.uno import ArduinoUno
from j5aio.components.derived.ultrasound import UltrasoundSensor
from j5aio.components.gpio_pin import GPIOPin, GPIOPinMode
from j5aio.components.led import LED

if TYPE_CHECKING:
    from j5aio.backends.backend import Backend
    from j5aio.components.component import Component
    from j5aio.components.gpio_pin import FirmwareMode

__all__ = ["AllDigitalUno"]


class AllDigitalUno(ArduinoUno):
    """An Uno whose pins 2 to 19 are all digital, with ultrasound on any pair of them.

    The base of the boards of today's kits (the SR Arduino with firmware 2, the
    SourceBots Arduino with sb2024): A0 to A5 (14 to 19) take the digital modes as well
    as ANALOGUE_INPUT, and ``board.ultrasound_sensors[trigger, echo]`` works on any two
    pins; its ``distance()`` is ``None`` when no echo comes back.

    :param serial_number: the board's serial number.
    :param backend: the backend that drives the board.
    """

    ANALOGUE_PIN_MODES: ClassVar[frozenset[GPIOPinMode]] = ArduinoUno.DIGITAL_PIN_MODES | {
        GPIOPinMode.ANALOGUE_INPUT,
    }
    DIGITAL_PIN_FIRMWARE_MODES: ClassVar[frozenset[FirmwareMode]] = frozenset(
        {UltrasoundSensor},
    )
    ANALOGUE_PIN_FIRMWARE_MODES: ClassVar[frozenset[FirmwareMode]] = DIGITAL_PIN_FIRMWARE_MODES

    def __init__(self, serial_number: str, backend: Backend) -> None:
        super().__init__(serial_number, backend)
        self._ultrasound_sensors = UltrasoundSensors(self)

    @property
    def ultrasound_sensors(self) -> UltrasoundSensors:
        """Ultrasound sensors on demand: ``board.ultrasound_sensors[trigger_pin, echo_pin]``."""
        return self._ultrasound_sensors

    @staticmethod
    def supported_components() -> set[type[Component]]:
        """The component classes on the board."""
        return {GPIOPin, LED, UltrasoundSensor}

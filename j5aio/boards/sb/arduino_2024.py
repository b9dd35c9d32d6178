"""The SourceBots Arduino running the sb2024 firmware: every pin digital, ultrasound, no servos."""

from __future__ import annotations

from typing import TYPE_CHECKING, ClassVar

from j5aio.boards.arduino.uno import ArduinoUno
from j5aio.boards.sb.arduino import UltrasoundSensors
from j5aio.components.derived.ultrasound import UltrasoundSensor
from j5aio.components.gpio_pin import GPIOPin, GPIOPinMode
from j5aio.components.led import LED

if TYPE_CHECKING:
    from j5aio.backends.backend import Backend
    from j5aio.components.component import Component
    from j5aio.components.gpio_pin import FirmwareMode

__all__ = ["SBArduino2024Board"]


class SBArduino2024Board(ArduinoUno):
    """The SourceBots Arduino of the 2024 kit (firmware ``2.0``, the sb2024 protocol).

    Every pin from 2 to 19 is a digital input, input with pull-up or output; A0 to A5
    (14 to 19) also read voltages. An ultrasound sensor works on any two pins:
    ``board.ultrasound_sensors[trigger, echo]``, whose ``distance()`` is ``None`` when
    no echo comes back. The firmware drives no servos.

    :param serial_number: the board's serial number.
    :param backend: the backend that drives the board.
    """

    name: ClassVar[str] = "SourceBots Arduino (sb2024)"

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
        """The component classes on a SourceBots Arduino (sb2024)."""
        return {GPIOPin, LED, UltrasoundSensor}

"""The SourceBots Arduino: an Arduino Uno whose firmware also drives servos and ultrasound.

Its :class:`~j5aio.boards.arduino.ultrasound.UltrasoundSensors` are the Uno family's
(:mod:`j5aio.boards.arduino.ultrasound`), importable from here too.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, ClassVar

from j5aio.boards.arduino.ultrasound import UltrasoundSensors
from j5aio.boards.arduino.uno import ArduinoUno
from j5aio.components.derived.ultrasound import UltrasoundSensor
from j5aio.components.gpio_pin import GPIOPin
from j5aio.components.led import LED
from j5aio.components.servo import Servo
from j5aio.numbered import NumberedComponents

if TYPE_CHECKING:
    from j5aio.backends.backend import Backend
    from j5aio.components.component import Component
    from j5aio.components.gpio_pin import FirmwareMode

__all__ = ["SBArduinoBoard", "UltrasoundSensors"]


class SBArduinoBoard(ArduinoUno):
    """The SourceBots Arduino.

    On top of an Uno's pins it drives 16 servos, and an ultrasound sensor on any pair of
    digital pins: ``board.ultrasound_sensors[trigger, echo]``.

    :param serial_number: the board's serial number.
    :param backend: the backend that drives the board.
    """

    name: ClassVar[str] = "SourceBots Arduino"

    #: The number of servos the firmware drives.
    SERVO_COUNT: ClassVar[int] = 16

    DIGITAL_PIN_FIRMWARE_MODES: ClassVar[frozenset[FirmwareMode]] = frozenset(
        {UltrasoundSensor},
    )

    def __init__(self, serial_number: str, backend: Backend) -> None:
        super().__init__(serial_number, backend)
        self._servos = NumberedComponents(
            (Servo(i, backend) for i in range(self.SERVO_COUNT)), owner=self, kind="servo",
        )
        self._ultrasound_sensors = UltrasoundSensors(self)

    @property
    def servos(self) -> tuple[Servo, ...]:
        """The servos, numbered 0 to 15."""
        return self._servos

    @property
    def ultrasound_sensors(self) -> UltrasoundSensors:
        """Ultrasound sensors on demand: ``board.ultrasound_sensors[trigger_pin, echo_pin]``."""
        return self._ultrasound_sensors

    @staticmethod
    def supported_components() -> set[type[Component]]:
        """The component classes on a SourceBots Arduino."""
        return {GPIOPin, LED, Servo, UltrasoundSensor}

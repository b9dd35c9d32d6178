"""The SourceBots Arduino: an Arduino Uno whose firmware also drives servos and ultrasound."""

from __future__ import annotations

from typing import TYPE_CHECKING, ClassVar

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


class UltrasoundSensors:
    """Makes an ultrasound sensor for a pair of pins when it is asked for by subscript.

    ``sensors[trigger, echo]`` gives a new
    :class:`~j5aio.components.derived.ultrasound.UltrasoundSensor` whose trigger is pin ``trigger``
    and whose echo is pin ``echo``, so sensors are reached with square brackets like every other
    kind of component.

    :param board: the board whose pins the sensors use.
    """

    def __init__(self, board: ArduinoUno) -> None:
        self._board = board

    def __getitem__(self, pins: tuple[int, int]) -> UltrasoundSensor:
        """Return an ultrasound sensor on the pin pair ``(trigger, echo)``.

        :raises TypeError: ``pins`` is not a pair of pin numbers.
        :raises KeyError: a pin number is not a pin of the board.
        """
        if not isinstance(pins, tuple) or len(pins) != 2:
            raise TypeError(
                "ultrasound_sensors needs a pair of pin numbers, as in "
                f"ultrasound_sensors[trigger_pin, echo_pin]; got {pins!r}",
            )
        trigger_pin, echo_pin = (self._pin(number) for number in pins)
        return UltrasoundSensor(
            trigger_pin,
            echo_pin,
            self._board.backend,
        )

    def _pin(self, number: int) -> GPIOPin:
        pins = self._board.pins
        if isinstance(number, bool) or not isinstance(number, int):
            raise TypeError(
                f"a pin number must be an int, not {type(number).__name__} ({number!r})",
            )
        if number not in pins:
            raise KeyError(
                f"{self._board.name} has no pin {number}; its pins are "
                f"{min(pins.keys())} to {max(pins.keys())}",
            )
        return pins[number]

    def __repr__(self) -> str:
        return f"<UltrasoundSensors of {self._board!r}>"

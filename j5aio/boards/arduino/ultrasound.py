"""Ultrasound sensors on any pair of an Arduino Uno's pins, made when they are asked for.

The boards whose firmware times ultrasound on any two pins (the SourceBots Arduino, and
every :class:`~j5aio.boards.arduino.all_digital.AllDigitalUno`) give
``board.ultrasound_sensors[trigger, echo]``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from j5aio.components.derived.ultrasound import UltrasoundSensor

if TYPE_CHECKING:
    from j5aio.boards.arduino.uno import ArduinoUno
    from j5aio.components.gpio_pin import GPIOPin

__all__ = ["UltrasoundSensors"]


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

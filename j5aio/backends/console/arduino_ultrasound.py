"""ArduinoUltrasoundConsoleBackend: an Arduino on the console whose firmware reads ultrasound."""

from __future__ import annotations

from datetime import timedelta

from j5aio.backends.console.arduino import ArduinoConsoleBackend
from j5aio.components.derived.ultrasound import UltrasoundInterface
from j5aio.components.gpio_pin import GPIOPinMode

__all__ = ["ArduinoUltrasoundConsoleBackend"]


class ArduinoUltrasoundConsoleBackend(UltrasoundInterface, ArduinoConsoleBackend):
    """The pins and LED of an Arduino Uno on the console, and ultrasound readings asked for.

    A subclass sets ``board``. An answer of 0 means no echo, as on the boards themselves.

    :param serial: the board's serial number.
    :param console_class: the console to talk through.
    """

    async def get_ultrasound_pulse(
        self, trigger_pin_identifier: int, echo_pin_identifier: int,
    ) -> timedelta | None:
        """Ask how long the echo took, in microseconds; an answer of 0 means no echo."""
        self._check_ultrasound_pins(trigger_pin_identifier, echo_pin_identifier)
        microseconds = await self._console.read(
            f"Response time for ultrasound sensor on pins "
            f"{trigger_pin_identifier}/{echo_pin_identifier} [microseconds]",
            float,
        )
        self._ultrasound_used(trigger_pin_identifier, echo_pin_identifier)
        # As on the board itself, a reading of 0 says that no echo came back.
        return timedelta(microseconds=microseconds) if microseconds else None

    async def get_ultrasound_distance(
        self, trigger_pin_identifier: int, echo_pin_identifier: int,
    ) -> float | None:
        """Ask for the distance to the nearest object, in metres; 0 means no echo."""
        self._check_ultrasound_pins(trigger_pin_identifier, echo_pin_identifier)
        metres = await self._console.read(
            f"Distance for ultrasound sensor on pins "
            f"{trigger_pin_identifier}/{echo_pin_identifier} [metres]",
            float,
        )
        self._ultrasound_used(trigger_pin_identifier, echo_pin_identifier)
        return metres or None

    def _check_ultrasound_pins(self, trigger: int, echo: int) -> None:
        for identifier in (trigger, echo):
            self._pin(identifier)

    def _ultrasound_used(self, trigger: int, echo: int) -> None:
        """Record the modes the firmware leaves the pins in after a measurement."""
        self._pins[trigger].mode = GPIOPinMode.DIGITAL_OUTPUT
        self._pins[trigger].digital_state = False
        self._pins[echo].mode = GPIOPinMode.DIGITAL_INPUT

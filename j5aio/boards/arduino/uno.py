"""The Arduino Uno, and the base of the boards built on it (Ruggeduino, SourceBots Arduino)."""

from __future__ import annotations

from enum import IntEnum
from typing import TYPE_CHECKING, ClassVar

from j5aio.boards.board import Board
from j5aio.components.gpio_pin import GPIOPin, GPIOPinMode
from j5aio.components.led import LED
from j5aio.numbered import Pins

if TYPE_CHECKING:
    from j5aio.backends.backend import Backend
    from j5aio.components.component import Component
    from j5aio.components.gpio_pin import FirmwareMode

__all__ = ["AnaloguePin", "ArduinoUno", "PinNumber"]


class ArduinoUno(Board):
    """An Arduino Uno: digital pins 2 to 13, analogue pins A0 to A5 and the LED on pin 13.

    Pins 0 and 1 carry the serial link to the computer, so they are not offered. Every pin
    is available from :attr:`pins`, by number (``board.pins[3]``) or, for the analogue
    pins, by name (``board.pins[ArduinoUno.AnaloguePin.A0]``, which is pin 14).

    :param serial_number: the board's serial number.
    :param backend: the backend that drives the board.
    """

    class AnaloguePin(IntEnum):
        """The analogue pins of the Uno, numbered after the digital ones."""

        A0 = 14
        A1 = 15
        A2 = 16
        A3 = 17
        A4 = 18
        A5 = 19

    name: ClassVar[str] = "Arduino Uno"

    #: The first analogue pin; the digital pins run from 2 up to just before it.
    FIRST_ANALOGUE_PIN: ClassVar[int] = AnaloguePin.A0

    #: The digital pins offered to users (0 and 1 carry the serial link).
    DIGITAL_PINS: ClassVar[range] = range(2, FIRST_ANALOGUE_PIN)

    #: The hardware modes of the digital pins.
    DIGITAL_PIN_MODES: ClassVar[frozenset[GPIOPinMode]] = frozenset(
        {
            GPIOPinMode.DIGITAL_INPUT,
            GPIOPinMode.DIGITAL_INPUT_PULLUP,
            GPIOPinMode.DIGITAL_OUTPUT,
        },
    )

    #: The hardware modes of the analogue pins. The Uno's chip could use them as digital
    #: pins too; a board whose firmware offers that (the Ruggeduino) widens this, and
    #: otherwise a digital mode is refused by the pin itself, before any traffic.
    ANALOGUE_PIN_MODES: ClassVar[frozenset[GPIOPinMode]] = frozenset(
        {GPIOPinMode.ANALOGUE_INPUT},
    )

    #: The firmware modes of the digital pins; a board whose firmware drives more widens it.
    DIGITAL_PIN_FIRMWARE_MODES: ClassVar[frozenset[FirmwareMode]] = frozenset()

    #: The firmware modes of the analogue pins (none unless the firmware drives them).
    ANALOGUE_PIN_FIRMWARE_MODES: ClassVar[frozenset[FirmwareMode]] = frozenset()

    def __init__(self, serial_number: str, backend: Backend) -> None:
        super().__init__(serial_number, backend)
        self._led = LED(0, backend)
        pins: dict[int, GPIOPin] = {
            number: GPIOPin(
                number,
                backend,
                initial_mode=GPIOPinMode.DIGITAL_INPUT,
                hardware_modes=self.DIGITAL_PIN_MODES,
                firmware_modes=self.DIGITAL_PIN_FIRMWARE_MODES,
            )
            for number in self.DIGITAL_PINS
        }
        for analogue_pin in ArduinoUno.AnaloguePin:
            pins[analogue_pin] = GPIOPin(
                int(analogue_pin),
                backend,
                initial_mode=GPIOPinMode.ANALOGUE_INPUT,
                hardware_modes=self.ANALOGUE_PIN_MODES,
                firmware_modes=self.ANALOGUE_PIN_FIRMWARE_MODES,
            )
        self._pins = Pins(pins, owner=self)

    @property
    def pins(self) -> Pins[GPIOPin]:
        """The GPIO pins, by number or by :class:`AnaloguePin`.

        Iterating gives the pins themselves, as in j5; ``pins.keys()`` gives the numbers.
        """
        return self._pins

    @property
    def led(self) -> LED:
        """The LED on the board, wired to digital pin 13."""
        return self._led

    @staticmethod
    def supported_components() -> set[type[Component]]:
        """The component classes on an Arduino Uno."""
        return {GPIOPin, LED}

    async def _setup(self) -> None:
        """Put every pin in its initial mode, in pin order."""
        for pin in self._pins.values():
            await pin.setup()

    async def make_safe(self) -> None:
        """Do nothing: a pin has no safe state that suits every circuit."""


AnaloguePin = ArduinoUno.AnaloguePin
"""The analogue pins of an Arduino Uno (the same enum as ``ArduinoUno.AnaloguePin``)."""

PinNumber = int | ArduinoUno.AnaloguePin
"""A pin of an Arduino Uno: its number, or the name of an analogue pin."""

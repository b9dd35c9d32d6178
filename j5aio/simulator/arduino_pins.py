"""The I/O pins of an Arduino Uno (ATmega328P), as the Arduino core functions see them.

Both Arduino simulators use this table. It reproduces the AVR port model behind
``pinMode``, ``digitalWrite``, ``digitalRead`` and ``analogRead``:

- each pin has a direction bit (DDR) and an output latch (PORT);
- ``pinMode(INPUT)`` clears both bits, ``pinMode(INPUT_PULLUP)`` clears the direction and
  sets the latch, ``pinMode(OUTPUT)`` sets the direction and keeps the latch;
- ``digitalWrite`` only sets the latch, so on a pin still in input mode it switches the
  internal pull-up on or off instead of driving the pin;
- ``digitalRead`` of an output reads back its latch; of an input, the level something
  outside drives, else HIGH with the pull-up on, else LOW (a floating pin, modelled low);
- ``analogRead`` accepts a channel (0-5) or a pin number (14-19), masks the channel to
  three bits as the core does, and reads the ADC whatever the pin's digital mode;
- pin numbers the core does not know (20 and up) are ignored, and read LOW.

The outside world (input levels, analogue voltages) is environment, not board state: it
survives a reboot.
"""

from __future__ import annotations

import enum
from typing import Final

__all__ = ["ADC_MAX", "ANALOGUE_PINS", "PIN_COUNT", "ArduinoUnoPins", "PinMode"]

#: Number of I/O pins: digital 0-13 and A0-A5 as 14-19.
PIN_COUNT: Final = 20
#: The pin number of A0.
FIRST_ANALOGUE_PIN: Final = 14
#: The pin numbers of A0-A5.
ANALOGUE_PINS: Final = range(FIRST_ANALOGUE_PIN, PIN_COUNT)
#: The largest ADC reading (10 bits).
ADC_MAX: Final = 1023
_ADC_STEPS: Final = 1024
_ADC_CHANNELS: Final = 8
_REFERENCE_VOLTS: Final = 5.0


class PinMode(enum.Enum):
    """The mode of a pin, derived from its direction bit and output latch."""

    INPUT = "INPUT"
    INPUT_PULLUP = "INPUT_PULLUP"
    OUTPUT = "OUTPUT"


class ArduinoUnoPins:
    """The pin state of an Arduino Uno plus what the outside world applies to its pins."""

    def __init__(self) -> None:
        self._output = [False] * PIN_COUNT
        self._latch = [False] * PIN_COUNT
        self._driven: list[bool | None] = [None] * PIN_COUNT
        self._adc = [0] * _ADC_CHANNELS

    def reset(self) -> None:
        """Put every pin in its power-on state: input, latch low, pull-up off."""
        self._output = [False] * PIN_COUNT
        self._latch = [False] * PIN_COUNT

    # --- the Arduino core functions the firmware calls ---

    def pin_mode(self, pin: int, mode: PinMode) -> None:
        """``pinMode(pin, mode)``."""
        if not self._exists(pin):
            return
        if mode is PinMode.OUTPUT:
            self._output[pin] = True
        else:
            self._output[pin] = False
            self._latch[pin] = mode is PinMode.INPUT_PULLUP

    def digital_write(self, pin: int, high: bool) -> None:
        """``digitalWrite(pin, HIGH / LOW)``."""
        if self._exists(pin):
            self._latch[pin] = high

    def digital_read(self, pin: int) -> bool:
        """``digitalRead(pin)``: True for HIGH."""
        if not self._exists(pin):
            return False
        if self._output[pin]:
            return self._latch[pin]
        driven = self._driven[pin]
        if driven is not None:
            return driven
        return self._latch[pin]

    def analog_read(self, pin: int) -> int:
        """``analogRead(pin)`` on an ATmega328P: channel or pin number, masked to 3 bits."""
        channel = pin & 0xFF
        if channel >= FIRST_ANALOGUE_PIN:
            channel -= FIRST_ANALOGUE_PIN
        return self._adc[channel & (_ADC_CHANNELS - 1)]

    # --- inspection ---

    def mode(self, pin: int) -> PinMode:
        """The mode pin ``pin`` is in."""
        self.check_pin(pin)
        if self._output[pin]:
            return PinMode.OUTPUT
        return PinMode.INPUT_PULLUP if self._latch[pin] else PinMode.INPUT

    def output_level(self, pin: int) -> bool:
        """The output latch of ``pin``: the level it drives in OUTPUT mode (pull-up if input)."""
        self.check_pin(pin)
        return self._latch[pin]

    def level(self, pin: int) -> bool:
        """The level the firmware would read on ``pin`` now."""
        self.check_pin(pin)
        return self.digital_read(pin)

    # --- the outside world ---

    def set_input_level(self, pin: int, level: bool | None) -> None:
        """Drive ``pin`` HIGH (True) or LOW (False) from outside, or let it float (None)."""
        self.check_pin(pin)
        self._driven[pin] = level

    def input_level(self, pin: int) -> bool | None:
        """The level the outside world drives on ``pin`` (None when floating)."""
        self.check_pin(pin)
        return self._driven[pin]

    def set_analogue(self, pin: int, *, volts: float | None = None, raw: int | None = None) -> None:
        """Apply a voltage to analogue pin ``pin`` (14-19), given in volts or as an ADC reading.

        Volts convert as the ADC does with a 5 V reference: ``floor(V * 1024 / 5)``,
        saturating at 0 and 1023.
        """
        channel = self._analogue_channel(pin)
        if volts is not None and raw is None:
            reading = max(0, min(ADC_MAX, int(volts * _ADC_STEPS / _REFERENCE_VOLTS)))
        elif raw is not None and volts is None:
            if not 0 <= raw <= ADC_MAX:
                raise ValueError(f"an ADC reading is 0-{ADC_MAX}, not {raw}")
            reading = raw
        else:
            raise TypeError("give exactly one of volts and raw")
        self._adc[channel] = reading

    def analogue(self, pin: int) -> int:
        """The ADC reading of analogue pin ``pin`` (14-19)."""
        return self._adc[self._analogue_channel(pin)]

    @staticmethod
    def _exists(pin: int) -> bool:
        return 0 <= pin < PIN_COUNT

    @staticmethod
    def check_pin(pin: int) -> None:
        """Raise IndexError unless ``pin`` is a pin of the Uno (0-19)."""
        if not 0 <= pin < PIN_COUNT:
            raise IndexError(f"an Arduino Uno has pins 0-{PIN_COUNT - 1}, not {pin}")

    @staticmethod
    def _analogue_channel(pin: int) -> int:
        if pin not in ANALOGUE_PINS:
            raise IndexError(f"the analogue pins are 14-19 (A0-A5), not {pin}")
        return pin - FIRST_ANALOGUE_PIN

"""The pin rules shared by every Arduino Uno backend (Ruggeduino, SourceBots Arduino).

Pins 2 to 13 are digital: input, input with pull-up, or output. Pins 14 to 19 (A0 to
A5) are analogue inputs, and digital pins as well where the firmware drives them
(``analogue_pins_digital``: the Ruggeduino's firmware 1; not the SourceBots 2019 one).
Pins 0 and 1 carry the serial link. The backend remembers each digital pin's mode and
the level last written to it, because the firmware cannot report either.

Pure rules, no I/O: the Arduino backends share them, so the errors are the same on
every board.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Final

from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.errors import NotSupportedByHardwareError

__all__ = [
    "ANALOGUE_PINS",
    "DIGITAL_MODES",
    "DIGITAL_PINS",
    "FIRST_ANALOGUE_PIN",
    "LED_PIN",
    "ArduinoPins",
    "DigitalPinState",
]

#: The first analogue pin (A0).
FIRST_ANALOGUE_PIN: Final = 14
#: The digital pins a user may drive.
DIGITAL_PINS: Final = range(2, FIRST_ANALOGUE_PIN)
#: The analogue pins, A0 to A5.
ANALOGUE_PINS: Final = range(FIRST_ANALOGUE_PIN, FIRST_ANALOGUE_PIN + 6)
#: The modes a digital pin can take.
DIGITAL_MODES: Final = frozenset(
    {GPIOPinMode.DIGITAL_INPUT, GPIOPinMode.DIGITAL_INPUT_PULLUP, GPIOPinMode.DIGITAL_OUTPUT},
)
#: The digital pin wired to the board's LED.
LED_PIN: Final = 13

_INPUT_MODES: Final = frozenset({GPIOPinMode.DIGITAL_INPUT, GPIOPinMode.DIGITAL_INPUT_PULLUP})


@dataclass
class DigitalPinState:
    """What the backend remembers about a digital pin."""

    mode: GPIOPinMode = GPIOPinMode.DIGITAL_INPUT
    level: bool = False


class ArduinoPins:
    """The remembered state of an Uno's pins, and the rules for what each pin may do.

    :param board_name: the board's name, for error messages.
    """

    def __init__(self, board_name: str, *, analogue_pins_digital: bool = False) -> None:
        self._board_name = board_name
        self._digital = {pin: DigitalPinState() for pin in DIGITAL_PINS}
        #: Whether A0 to A5 take the digital modes too (the firmware drives them).
        self.analogue_pins_digital = analogue_pins_digital
        if analogue_pins_digital:
            for pin in ANALOGUE_PINS:
                self._digital[pin] = DigitalPinState(mode=GPIOPinMode.ANALOGUE_INPUT)

    def digital(self, pin: int) -> DigitalPinState:
        """Return the state of digital ``pin``.

        :raises NotSupportedByHardwareError: ``pin`` is an analogue pin.
        :raises ValueError: ``pin`` is not a pin of the board.
        """
        self._check_exists(pin)
        if pin in ANALOGUE_PINS and not self.analogue_pins_digital:
            raise NotSupportedByHardwareError(
                f"{self._board_name} pin {pin} is an analogue input; digital functions are "
                f"available on pins {DIGITAL_PINS.start} to {DIGITAL_PINS.stop - 1} only",
            )
        return self._digital[pin]

    def mode(self, pin: int) -> GPIOPinMode:
        """Return the mode of ``pin`` (analogue pins are always ANALOGUE_INPUT)."""
        self._check_exists(pin)
        if pin in ANALOGUE_PINS and not self.analogue_pins_digital:
            return GPIOPinMode.ANALOGUE_INPUT
        return self._digital[pin].mode

    def check_mode(self, pin: int, mode: GPIOPinMode) -> bool:
        """Check that ``pin`` can take ``mode``; return whether the board needs telling.

        :raises NotSupportedByHardwareError: the pin cannot take that mode.
        :raises ValueError: ``pin`` is not a pin of the board.
        """
        self._check_exists(pin)
        if pin in ANALOGUE_PINS and mode is GPIOPinMode.ANALOGUE_INPUT:
            # back from a digital mode, the pin must stop driving: the board is told
            return self.analogue_pins_digital and self._digital[pin].mode is not mode
        if mode in DIGITAL_MODES and (pin in DIGITAL_PINS or self.analogue_pins_digital):
            return True
        allowed = (
            ", ".join(sorted(m.name for m in DIGITAL_MODES | {GPIOPinMode.ANALOGUE_INPUT}))
            if pin in ANALOGUE_PINS and self.analogue_pins_digital
            else "ANALOGUE_INPUT"
            if pin in ANALOGUE_PINS
            else ", ".join(sorted(m.name for m in DIGITAL_MODES))
        )
        raise NotSupportedByHardwareError(
            f"{self._board_name} pin {pin} cannot be put in mode {mode.name}; it supports "
            f"{allowed}",
        )

    def output(self, pin: int, action: str) -> DigitalPinState:
        """Return the state of ``pin`` for an output operation (``action`` names it).

        :raises ValueError: the pin is not in DIGITAL_OUTPUT mode.
        """
        state = self.digital(pin)
        if state.mode is not GPIOPinMode.DIGITAL_OUTPUT:
            raise ValueError(
                f"{self._board_name} pin {pin} must be in DIGITAL_OUTPUT mode to {action}; it "
                f"is in {state.mode.name}",
            )
        return state

    def check_input(self, pin: int) -> None:
        """Check that ``pin`` is a digital input, for a read.

        :raises ValueError: the pin is not in an input mode.
        """
        state = self.digital(pin)
        if state.mode not in _INPUT_MODES:
            raise ValueError(
                f"{self._board_name} pin {pin} must be in DIGITAL_INPUT or "
                f"DIGITAL_INPUT_PULLUP mode to read it; it is in {state.mode.name}",
            )

    def check_analogue(self, pin: int, channels: int = len(ANALOGUE_PINS)) -> None:
        """Check that ``pin`` is one of the first ``channels`` analogue pins.

        :raises NotSupportedByHardwareError: it is a digital pin, or beyond ``channels``.
        """
        self._check_exists(pin)
        last = FIRST_ANALOGUE_PIN + channels - 1
        if not FIRST_ANALOGUE_PIN <= pin <= last:
            raise NotSupportedByHardwareError(
                f"{self._board_name} can read analogue values on pins {FIRST_ANALOGUE_PIN} "
                f"to {last} only, not pin {pin}",
            )

    @staticmethod
    def check_led(identifier: int, board_name: str) -> None:
        """Check that ``identifier`` is LED 0, the only LED (on pin 13).

        :raises ValueError: any other identifier.
        """
        if identifier != 0:
            raise ValueError(f"{board_name} has only LED 0 (on pin 13), not LED {identifier!r}")

    def _check_exists(self, pin: int) -> None:
        if isinstance(pin, bool) or not isinstance(pin, int):
            raise TypeError(f"a pin number must be an int, not {type(pin).__name__}")
        if pin not in DIGITAL_PINS and pin not in ANALOGUE_PINS:
            raise ValueError(
                f"{self._board_name} has pins {DIGITAL_PINS.start} to {ANALOGUE_PINS.stop - 1}, "
                f"not pin {pin}",
            )

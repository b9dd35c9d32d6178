"""The pin rules of every Arduino Uno backend, in one table (Ruggeduino, SB and SR Arduinos).

Pins 2 to 13 are digital: input, input with pull-up, or output. Pins 14 to 19 (A0 to
A5) are analogue inputs, and digital pins as well where the firmware drives them
(``analogue_pins_digital``: the Ruggeduino's firmware 1, the SR Arduino's firmware 2 and
the SourceBots 2024 firmware; not the SourceBots 2019 one). Pins 0 and 1 carry the
serial link. The backend remembers each pin's mode and the level last written to it,
because the firmware cannot report either.

Two firmware families treat ANALOGUE_INPUT differently, and :class:`ArduinoPins` says
which with ``analogue_mode_required``:

* the Ruggeduino's and SourceBots 2019 firmwares read an analogue pin whatever its
  digital mode; A0 to A5 start in ANALOGUE_INPUT;
* the firmwares that let every pin be digital (SR fw 2, SB sb2024) start every pin as a
  digital input, and read a voltage only from a pin put in ANALOGUE_INPUT, which is a
  plain input on the wire (:func:`wire_mode`): the ADC reads the pin whatever its
  digital mode, and an input without pull-up does not disturb the reading.

Pure rules, no I/O: every Arduino backend shares them, so the errors are the same on
every board. A backend checks first, tells the board, then records what the board now
does (:meth:`ArduinoPins.record`); :meth:`ArduinoPins.reset` is all a "the board came
back" hook needs to call.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Final

from j5aio._records import Record
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.errors import NotSupportedByHardwareError

__all__ = [
    "ANALOGUE_PINS",
    "DIGITAL_MODES",
    "DIGITAL_PINS",
    "FIRST_ANALOGUE_PIN",
    "LED_PIN",
    "PINS",
    "ArduinoPins",
    "DigitalPinState",
    "wire_mode",
]

#: The first analogue pin (A0).
FIRST_ANALOGUE_PIN: Final = 14
#: The digital pins a user may drive.
DIGITAL_PINS: Final = range(2, FIRST_ANALOGUE_PIN)
#: The analogue pins, A0 to A5.
ANALOGUE_PINS: Final = range(FIRST_ANALOGUE_PIN, FIRST_ANALOGUE_PIN + 6)
#: Every pin a user may use: 2 to 13 and A0 to A5 (14 to 19).
PINS: Final = range(DIGITAL_PINS.start, ANALOGUE_PINS.stop)
#: The modes a digital pin can take.
DIGITAL_MODES: Final = frozenset(
    {GPIOPinMode.DIGITAL_INPUT, GPIOPinMode.DIGITAL_INPUT_PULLUP, GPIOPinMode.DIGITAL_OUTPUT},
)
#: The digital pin wired to the board's LED.
LED_PIN: Final = 13

_INPUT_MODES: Final = frozenset({GPIOPinMode.DIGITAL_INPUT, GPIOPinMode.DIGITAL_INPUT_PULLUP})
_ANALOGUE_PIN_MODES: Final = DIGITAL_MODES | {GPIOPinMode.ANALOGUE_INPUT}


def wire_mode(mode: GPIOPinMode) -> GPIOPinMode:
    """Return the digital mode the board is sent for ``mode``: ANALOGUE_INPUT is an input."""
    return GPIOPinMode.DIGITAL_INPUT if mode is GPIOPinMode.ANALOGUE_INPUT else mode


# (It writes its own ``__init__`` and takes ``__repr__`` and ``__eq__`` from Record, as
# ``@dataclass`` would make them: every program with an Arduino imports it, and making the
# generated ones costs a tenth of a millisecond. A test checks them against those.)
@dataclass(init=False, repr=False, eq=False)
class DigitalPinState(Record):
    """What the backend remembers about a digital pin."""

    mode: GPIOPinMode = GPIOPinMode.DIGITAL_INPUT
    level: bool = False

    def __init__(self, mode: GPIOPinMode = GPIOPinMode.DIGITAL_INPUT, level: bool = False) -> None:
        self.mode = mode
        self.level = level


class ArduinoPins:
    """The remembered state of an Uno's pins, and the rules for what each pin may do.

    :param board_name: the board's name, for error messages.
    :param analogue_pins_digital: whether the firmware drives A0 to A5 as digital pins too.
    :param analogue_mode_required: whether a voltage is read only from a pin put in
        ANALOGUE_INPUT (the firmwares that let every pin be digital); then every pin
        starts as a digital input. Implies ``analogue_pins_digital``.
    """

    def __init__(
        self,
        board_name: str,
        *,
        analogue_pins_digital: bool = False,
        analogue_mode_required: bool = False,
    ) -> None:
        self._board_name = board_name
        #: Whether A0 to A5 take the digital modes too (the firmware drives them).
        self.analogue_pins_digital = analogue_pins_digital or analogue_mode_required
        #: Whether an analogue reading needs the pin in ANALOGUE_INPUT mode.
        self.analogue_mode_required = analogue_mode_required
        self._pins: dict[int, DigitalPinState] = {}
        self.reset()

    def reset(self) -> None:
        """Forget everything: every pin as after power-on (an input, its latch low)."""
        self._pins = {pin: DigitalPinState() for pin in DIGITAL_PINS}
        if self.analogue_pins_digital:
            start = (
                GPIOPinMode.DIGITAL_INPUT
                if self.analogue_mode_required
                else GPIOPinMode.ANALOGUE_INPUT
            )
            for pin in ANALOGUE_PINS:
                self._pins[pin] = DigitalPinState(mode=start)

    def digital(self, pin: int) -> DigitalPinState:
        """Return the remembered state of digital ``pin`` (the table's own, not a copy).

        :raises TypeError: ``pin`` is not an int.
        :raises NotSupportedByHardwareError: ``pin`` is an analogue-only pin.
        :raises ValueError: ``pin`` is not a pin of the board.
        """
        self._check_exists(pin)
        if pin in ANALOGUE_PINS and not self.analogue_pins_digital:
            raise NotSupportedByHardwareError(
                f"{self._board_name} pin {pin} is an analogue input; digital functions are "
                f"available on pins {DIGITAL_PINS.start} to {DIGITAL_PINS.stop - 1} only",
            )
        return self._pins[pin]

    def state(self, pin: int) -> DigitalPinState:
        """Return a copy of what is remembered of digital ``pin``; see :meth:`digital`."""
        state = self.digital(pin)
        return DigitalPinState(state.mode, state.level)

    def mode(self, pin: int) -> GPIOPinMode:
        """Return the mode of ``pin`` (an analogue-only pin is always ANALOGUE_INPUT).

        :raises TypeError: ``pin`` is not an int.
        :raises ValueError: ``pin`` is not a pin of the board.
        """
        self._check_exists(pin)
        if pin in ANALOGUE_PINS and not self.analogue_pins_digital:
            return GPIOPinMode.ANALOGUE_INPUT
        return self._pins[pin].mode

    def check_mode(self, pin: int, mode: GPIOPinMode) -> bool:
        """Check that ``pin`` can take ``mode``; return whether the board needs telling.

        It does not when an analogue pin is put in ANALOGUE_INPUT and is already there, or
        can only be there; a firmware whose ANALOGUE_INPUT is a plain input may tell it
        anyway.

        :raises NotSupportedByHardwareError: the pin cannot take that mode.
        :raises ValueError: ``pin`` is not a pin of the board.
        """
        self._check_exists(pin)
        if pin in ANALOGUE_PINS and mode is GPIOPinMode.ANALOGUE_INPUT:
            # back from a digital mode, the pin must stop driving: the board is told
            return self.analogue_pins_digital and self._pins[pin].mode is not mode
        if mode in DIGITAL_MODES and (pin in DIGITAL_PINS or self.analogue_pins_digital):
            return True
        if pin in DIGITAL_PINS:
            allowed = DIGITAL_MODES
        elif self.analogue_pins_digital:
            allowed = _ANALOGUE_PIN_MODES
        else:
            allowed = frozenset({GPIOPinMode.ANALOGUE_INPUT})
        raise NotSupportedByHardwareError(
            f"{self._board_name} pin {pin} cannot be put in mode {mode.name}; it supports "
            f"{', '.join(sorted(m.name for m in allowed))}",
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
        """Check that ``pin`` is one of the first ``channels`` analogue pins, for a reading.

        With ``analogue_mode_required``, it must also be in ANALOGUE_INPUT mode.

        :raises NotSupportedByHardwareError: it is a digital pin, or beyond ``channels``.
        :raises ValueError: it is not in ANALOGUE_INPUT mode, where that is required.
        """
        mode = self.mode(pin)
        last = FIRST_ANALOGUE_PIN + channels - 1
        if not FIRST_ANALOGUE_PIN <= pin <= last:
            raise NotSupportedByHardwareError(
                f"{self._board_name} can read analogue values on pins {FIRST_ANALOGUE_PIN} "
                f"to {last} (A0 to A{channels - 1}) only, not pin {pin}",
            )
        if self.analogue_mode_required and mode is not GPIOPinMode.ANALOGUE_INPUT:
            raise ValueError(
                f"{self._board_name} pin {pin} must be in ANALOGUE_INPUT mode to read a "
                f"voltage; it is in {mode.name}",
            )

    def record(
        self,
        pin: int,
        *,
        mode: GPIOPinMode | None = None,
        level: bool | None = None,
    ) -> None:
        """Remember what the board has been told: ``pin``'s new mode and/or level."""
        state = self.digital(pin)
        if mode is not None:
            state.mode = mode
        if level is not None:
            state.level = level

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
        if pin not in PINS:
            raise ValueError(
                f"{self._board_name} has pins {PINS.start} to {PINS.stop - 1}, not pin {pin}",
            )

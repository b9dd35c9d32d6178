"""sbot's ``arduino``: the SourceBots Arduino's pins, read and written as sbot does.

sbot sends pin commands as they come and lets the firmware decide; j5aio's pins check
each use against the pin's mode. The two agree on what the board ends up doing: this
module keeps j5aio's pin in the mode that matches what sbot would have told the board.

- ``INPUT`` is j5aio's ``ANALOGUE_INPUT`` on A0 to A5 and ``DIGITAL_INPUT`` on the others
  (both are a plain input on the wire); a digital read of A0 to A5 or an analogue read
  of a pin put in ``DIGITAL_INPUT`` switches between the two, which changes nothing on
  the board.
- A digital read of an output gives the level last written to it.
- A digital write to an input sets its pull-up, as the firmware does: ``True`` makes it
  ``INPUT_PULLUP``, ``False`` ``INPUT``.
- An analogue read of a pin in ``INPUT_PULLUP`` or ``OUTPUT`` mode raises ``IOError``
  (sbot would read a voltage the pull-up or the output disturbs).
"""

from __future__ import annotations

from collections.abc import Callable
from enum import Enum, IntEnum
from typing import TYPE_CHECKING, TypeVar, cast

from j5aio.components.gpio_pin import GPIOPinMode as Core
from j5aio.errors import BadGPIOPinModeError

from ._checks import map_to_float
from ._errors import translate_errors
from ._kit import KitLink

if TYPE_CHECKING:
    from j5aio.sync import GPIOPin


T = TypeVar("T")

__all__ = [
    "ADC_MAX",
    "ADC_MIN",
    "AVAILABLE_PINS",
    "DISABLED_PINS",
    "AnalogPin",
    "Arduino",
    "GPIOPinMode",
]


class GPIOPinMode(str, Enum):  # noqa: UP042 - sbot's str() of a mode
    """The modes of a pin."""

    INPUT = "INPUT"
    INPUT_PULLUP = "INPUT_PULLUP"
    OUTPUT = "OUTPUT"


class AnalogPin(IntEnum):
    """The analogue pins, by their pin numbers."""

    A0 = 14
    A1 = 15
    A2 = 16
    A3 = 17
    A4 = 18
    A5 = 19


#: The pins of the serial link to the brain.
DISABLED_PINS = (0, 1)
#: Every pin number of the Arduino.
AVAILABLE_PINS = range(0, max(AnalogPin) + 1)
#: The largest reading of the 10-bit ADC.
ADC_MAX = 1023
#: The smallest reading of the ADC.
ADC_MIN = 0
#: The steps j5aio's sb2024 codec divides 5 V into (volts = reading / 1024 x 5).
_J5AIO_ADC_STEPS = 1024
_ANALOGUE_PINS = frozenset(AnalogPin)
_DIGITAL_INPUTS = frozenset({Core.DIGITAL_INPUT, Core.DIGITAL_INPUT_PULLUP})


@translate_errors
class Arduino:
    """The Arduino running the sb2024 firmware.

    Each pin's j5aio mode is remembered here, so that a read or a write is one call to
    the board; if the board's mode changed behind this module's back (the board came
    back after a reset), the mode is read again and the call retried once.

    :param boards: the kit the Arduino is found on.
    """

    __slots__ = ("_boards", "_modes", "_pins")

    def __init__(self, boards: KitLink) -> None:
        self._boards = boards
        self._modes: dict[int, Core] = {}
        # The facade's pins, each looked up once (a lookup costs as much as a call).
        self._pins: dict[int, GPIOPin] = {}

    def _pin(self, pin: int) -> GPIOPin:
        board = self._boards.arduino()
        found = self._pins.get(pin)
        if found is None:
            _validate_pin(pin)
            found = self._pins[pin] = board.pins[pin]
        return found

    def _mode(self, pin: int, target: GPIOPin) -> Core:
        """The j5aio mode ``pin`` is in (remembered, or asked for the first time)."""
        mode = self._modes.get(pin)
        if mode is None:
            mode = self._modes[pin] = _core_mode(target.mode)
        return mode

    def _set_mode(self, pin: int, target: GPIOPin, mode: Core) -> None:
        self._modes.pop(pin, None)  # (unknown until the board has taken it)
        target.mode = mode
        self._modes[pin] = mode

    def _with_mode(self, pin: int, call: Callable[[GPIOPin, Core], T]) -> T:
        """Run ``call(pin, its mode)``; if the mode was stale, read it and run it again."""
        target = self._pin(pin)
        try:
            return call(target, self._mode(pin, target))
        except BadGPIOPinModeError:
            self._modes.pop(pin, None)
            return call(target, self._mode(pin, target))

    def set_pin_mode(self, pin: int, mode: GPIOPinMode) -> None:
        """Put ``pin`` in ``mode``: INPUT or INPUT_PULLUP to read it, OUTPUT to write it.

        :raises IOError: ``mode`` is not a :class:`GPIOPinMode`, or the pin is 0 or 1.
        :raises IndexError: there is no such pin.
        """
        target = self._pin(pin)
        if not isinstance(mode, GPIOPinMode):
            raise OSError("Pin mode only supports being set to a GPIOPinMode")
        if mode is GPIOPinMode.OUTPUT:
            self._set_mode(pin, target, Core.DIGITAL_OUTPUT)
        elif mode is GPIOPinMode.INPUT_PULLUP:
            self._set_mode(pin, target, Core.DIGITAL_INPUT_PULLUP)
        else:
            self._set_mode(pin, target, _plain_input(pin))

    def digital_read(self, pin: int) -> bool:
        """Read ``pin``'s level (an output gives the level last written to it).

        :raises IOError: the pin is 0 or 1.
        :raises IndexError: there is no such pin.
        """
        target = self._pin(pin)
        if self._modes.get(pin) in _DIGITAL_INPUTS:  # (the usual case: one call)
            try:
                return target.digital_read()
            except BadGPIOPinModeError:
                self._modes.pop(pin, None)

        def read(target: GPIOPin, mode: Core) -> bool:
            if mode is Core.DIGITAL_OUTPUT:
                return target.last_digital_write
            if mode is Core.ANALOGUE_INPUT:
                self._set_mode(pin, target, Core.DIGITAL_INPUT)
            return target.digital_read()

        return self._with_mode(pin, read)

    def digital_write(self, pin: int, value: bool) -> None:
        """Drive output ``pin`` high or low (on an input: switch its pull-up on or off).

        :raises IOError: the pin is 0 or 1.
        :raises IndexError: there is no such pin.
        """
        def write(target: GPIOPin, mode: Core) -> None:
            if mode is Core.DIGITAL_OUTPUT:
                target.digital_write(bool(value))
            elif value:
                self._set_mode(pin, target, Core.DIGITAL_INPUT_PULLUP)
            else:
                self._set_mode(pin, target, _plain_input(pin))

        self._with_mode(pin, write)

    def analog_read(self, pin: int) -> float:
        """Return the voltage on analogue ``pin`` (A0 to A5), 0 to 5 V.

        :raises IOError: the pin is not an analogue pin, or it is not in INPUT mode.
        :raises IndexError: there is no such pin.
        """
        target = self._pin(pin)
        if pin not in _ANALOGUE_PINS:
            raise OSError("Pin does not support analog read")

        def read(target: GPIOPin, mode: Core) -> float:
            if mode is Core.DIGITAL_INPUT:
                self._set_mode(pin, target, Core.ANALOGUE_INPUT)
            elif mode is not Core.ANALOGUE_INPUT:
                raise OSError(
                    f"Pin {pin} is in {_sbot_mode_name(mode)} mode: analog_read needs it in "
                    f"INPUT mode (arduino.set_pin_mode({pin}, GPIOPinMode.INPUT))",
                )
            return target.analogue_read()

        volts: float | None = None
        if self._modes.get(pin) is Core.ANALOGUE_INPUT:  # (the usual case: one call)
            try:
                volts = target.analogue_read()
            except BadGPIOPinModeError:
                self._modes.pop(pin, None)
        if volts is None:
            volts = self._with_mode(pin, read)
        # j5aio's codec gives volts as reading / 1024 x 5; sbot maps 0-1023 onto 0-5 V.
        reading = round(volts / 5 * _J5AIO_ADC_STEPS)
        return map_to_float(reading, ADC_MIN, ADC_MAX, 0.0, 5.0)

    def measure_ultrasound_distance(self, pulse_pin: int, echo_pin: int) -> int:
        """Return the distance an ultrasound sensor measures, in mm (0: no echo).

        The firmware leaves the pulse pin a low output and the echo pin an input.

        :raises ValueError: either pin is not a usable pin.
        """
        board = self._boards.arduino()
        try:
            _validate_pin(pulse_pin)
        except (IndexError, OSError):
            raise ValueError("Invalid pulse pin provided") from None
        try:
            _validate_pin(echo_pin)
        except (IndexError, OSError):
            raise ValueError("Invalid echo pin provided") from None
        self._modes.pop(pulse_pin, None)
        self._modes.pop(echo_pin, None)
        metres = board.ultrasound_sensors[pulse_pin, echo_pin].distance()
        self._modes[pulse_pin] = Core.DIGITAL_OUTPUT
        self._modes[echo_pin] = Core.DIGITAL_INPUT
        return 0 if metres is None else round(metres * 1000)

    def __repr__(self) -> str:
        if not self._boards.arduinos:
            return f"<{self.__class__.__qualname__} no arduino connected>"
        return f"<{self.__class__.__qualname__} {self._boards.arduinos[0].serial_number}>"


def _validate_pin(pin: int) -> None:
    if pin in DISABLED_PINS:
        raise OSError("This pin cannot be controlled.")
    if pin not in AVAILABLE_PINS:
        raise IndexError(f"Pin {pin} is not available on the Arduino.")


def _core_mode(mode: object) -> Core:
    """A pin's mode as j5aio's :class:`~j5aio.components.gpio_pin.GPIOPinMode`."""
    return Core(cast(int, mode))


def _plain_input(pin: int) -> Core:
    """j5aio's mode for sbot's INPUT on ``pin``: analogue input on A0 to A5."""
    from j5aio.components.gpio_pin import GPIOPinMode as Core

    return Core.ANALOGUE_INPUT if pin >= AnalogPin.A0 else Core.DIGITAL_INPUT


def _sbot_mode_name(mode: object) -> str:
    """Return the name sbot gives j5aio's pin mode ``mode``."""
    names = {"DIGITAL_OUTPUT": "OUTPUT", "DIGITAL_INPUT_PULLUP": "INPUT_PULLUP"}
    name = str(getattr(mode, "name", mode))
    return names.get(name, name)

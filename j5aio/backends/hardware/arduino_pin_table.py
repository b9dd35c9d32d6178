"""The pin rules of the Arduino firmwares that let every pin be digital (SR fw 2, SB sb2024).

Pins 2 to 19 are digital (input, input with pull-up, output); A0 to A5 (14 to 19) are
also analogue inputs. ANALOGUE_INPUT is a plain input on the wire: the ADC reads the pin
whatever its digital mode, and an input without pull-up does not disturb the reading.
Pins 0 and 1 carry the serial link.

The table remembers each pin's mode and the level last written to it. It holds the
backend's only cached board state, so :meth:`PinTable.reset` is all a "the board came
back" hook needs to call. Pure rules, no I/O: a backend checks first, tells the board,
then records what the board now does (:meth:`PinTable.record`).
"""

from __future__ import annotations

from typing import Final

from j5aio.backends.hardware.arduino_pins import (
    ANALOGUE_PINS,
    DIGITAL_MODES,
    DigitalPinState,
)
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.errors import NotSupportedByHardwareError

__all__ = ["PINS", "PinTable", "wire_mode"]

#: Every pin a user may use: 2 to 13 and A0 to A5 (14 to 19).
PINS: Final = range(2, ANALOGUE_PINS.stop)

_INPUT_MODES: Final = frozenset({GPIOPinMode.DIGITAL_INPUT, GPIOPinMode.DIGITAL_INPUT_PULLUP})
_ANALOGUE_MODES: Final = DIGITAL_MODES | {GPIOPinMode.ANALOGUE_INPUT}


def wire_mode(mode: GPIOPinMode) -> GPIOPinMode:
    """Return the digital mode the board is sent for ``mode``: ANALOGUE_INPUT is an input."""
    return GPIOPinMode.DIGITAL_INPUT if mode is GPIOPinMode.ANALOGUE_INPUT else mode


class PinTable:
    """The remembered state of pins 2 to 19, and the rules for what each pin may do.

    :param board_name: the board's name, for error messages.
    """

    def __init__(self, board_name: str) -> None:
        self._board_name = board_name
        self._pins = {pin: DigitalPinState() for pin in PINS}

    def reset(self) -> None:
        """Forget everything: every pin as after power-on (input, latch low)."""
        self._pins = {pin: DigitalPinState() for pin in PINS}

    def state(self, pin: int) -> DigitalPinState:
        """Return a copy of what is remembered of ``pin``.

        :raises TypeError: ``pin`` is not an int.
        :raises ValueError: ``pin`` is not a pin of the board.
        """
        state = self._get(pin)
        return DigitalPinState(state.mode, state.level)

    def mode(self, pin: int) -> GPIOPinMode:
        """Return the mode ``pin`` was last put in."""
        return self._get(pin).mode

    def check_mode(self, pin: int, mode: GPIOPinMode) -> None:
        """Check that ``pin`` can take ``mode``.

        :raises NotSupportedByHardwareError: it cannot.
        :raises ValueError: ``pin`` is not a pin of the board.
        """
        self._get(pin)
        allowed = _ANALOGUE_MODES if pin in ANALOGUE_PINS else DIGITAL_MODES
        if mode not in allowed:
            raise NotSupportedByHardwareError(
                f"{self._board_name} pin {pin} cannot be put in mode {mode.name}; it "
                f"supports {', '.join(sorted(m.name for m in allowed))}",
            )

    def check_output(self, pin: int, action: str) -> DigitalPinState:
        """Return a copy of ``pin``'s state for an output operation (``action`` names it).

        :raises ValueError: the pin is not in DIGITAL_OUTPUT mode.
        """
        state = self.state(pin)
        if state.mode is not GPIOPinMode.DIGITAL_OUTPUT:
            raise ValueError(
                f"{self._board_name} pin {pin} must be in DIGITAL_OUTPUT mode to {action}; "
                f"it is in {state.mode.name}",
            )
        return state

    def check_input(self, pin: int) -> None:
        """Check that ``pin`` is a digital input, for a digital read.

        :raises ValueError: it is not.
        """
        mode = self.mode(pin)
        if mode not in _INPUT_MODES:
            raise ValueError(
                f"{self._board_name} pin {pin} must be in DIGITAL_INPUT or "
                f"DIGITAL_INPUT_PULLUP mode to read it; it is in {mode.name}",
            )

    def check_analogue(self, pin: int) -> None:
        """Check that ``pin`` is an analogue pin in ANALOGUE_INPUT mode, for a reading.

        :raises NotSupportedByHardwareError: it is not an analogue pin.
        :raises ValueError: it is not in ANALOGUE_INPUT mode.
        """
        mode = self.mode(pin)
        if pin not in ANALOGUE_PINS:
            raise NotSupportedByHardwareError(
                f"{self._board_name} reads analogue values on pins {ANALOGUE_PINS.start} to "
                f"{ANALOGUE_PINS.stop - 1} (A0 to A5) only, not pin {pin}",
            )
        if mode is not GPIOPinMode.ANALOGUE_INPUT:
            raise ValueError(
                f"{self._board_name} pin {pin} must be in ANALOGUE_INPUT mode to read a "
                f"voltage; it is in {mode.name}",
            )

    def record(
        self, pin: int, *, mode: GPIOPinMode | None = None, level: bool | None = None,
    ) -> None:
        """Remember what the board has been told: ``pin``'s new mode and/or level."""
        state = self._get(pin)
        if mode is not None:
            state.mode = mode
        if level is not None:
            state.level = level

    def _get(self, pin: int) -> DigitalPinState:
        if isinstance(pin, bool) or not isinstance(pin, int):
            raise TypeError(f"a pin number must be an int, not {type(pin).__name__}")
        try:
            return self._pins[pin]
        except KeyError:
            raise ValueError(
                f"{self._board_name} has pins {PINS.start} to {PINS.stop - 1}, not pin {pin}",
            ) from None

"""What the outside world applies to a simulated Arduino's pins, from command-line text.

``python -m j5aio simulate sb-arduino --analog A0=2.5 --digital 3=1`` holds 2.5 V on A0
and pin 3 high. :func:`parse_analog` and :func:`parse_digital` read one such option
each, and :func:`apply_pin_options` applies them to a simulator.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import Final

from .arduino_base import ArduinoBoardSimulator

__all__ = ["apply_pin_options", "parse_analog", "parse_digital"]

#: The analogue pins by name, and their pin numbers.
_ANALOGUE: Final = {f"A{channel}": 14 + channel for channel in range(6)}
#: The pins an input level may be held on: 2 to 13 and A0 to A5 (0 and 1 carry serial).
_DIGITAL: Final = range(2, 20)
_REFERENCE_VOLTS: Final = 5.0


def _split(text: str, example: str) -> tuple[str, str]:
    pin, equals, value = text.partition("=")
    if not equals or not pin.strip() or not value.strip():
        raise ValueError(f"{text!r} is not PIN=VALUE (for example {example})")
    return pin.strip().upper(), value.strip()


def parse_analog(text: str) -> tuple[int, float]:
    """Read ``A0=2.5``: an analogue pin (A0 to A5) and the volts on it (0 to 5).

    :returns: the pin number (14 to 19) and the volts.
    :raises ValueError: the text, the pin or the voltage is not allowed (the message says
        what is).
    """
    pin, value = _split(text, "A0=2.5")
    number = _ANALOGUE.get(pin)
    if number is None:
        raise ValueError(f"{pin!r} is not an analogue pin: use A0 to A5 (in {text!r})")
    try:
        volts = float(value)
    except ValueError:
        raise ValueError(f"{value!r} is not a number of volts (in {text!r})") from None
    if math.isnan(volts) or not 0 <= volts <= _REFERENCE_VOLTS:
        raise ValueError(f"{value} V is out of range: give 0 to 5 V (in {text!r})")
    return number, volts


def parse_digital(text: str) -> tuple[int, bool]:
    """Read ``3=1``: a pin (2 to 13, or A0 to A5) and the level held on it (0 or 1).

    :returns: the pin number and whether it is held high.
    :raises ValueError: the text, the pin or the level is not allowed (the message says
        what is).
    """
    pin, value = _split(text, "3=1")
    number = _ANALOGUE.get(pin)
    if number is None:
        try:
            number = int(pin)
        except ValueError:
            number = -1
        if number not in _DIGITAL:
            raise ValueError(
                f"{pin!r} is not a pin an input can be held on: use 2 to 13 or A0 to A5 "
                f"(in {text!r})"
            )
    if value not in ("0", "1"):
        raise ValueError(f"{value!r} is not a level: use 0 (low) or 1 (high) (in {text!r})")
    return number, value == "1"


def apply_pin_options(
    simulator: object,
    analog: Iterable[tuple[int, float]] = (),
    digital: Iterable[tuple[int, bool]] = (),
) -> None:
    """Hold the given volts and levels on ``simulator``'s pins.

    :raises TypeError: there are pin options but ``simulator`` is not an Arduino.
    """
    analog, digital = list(analog), list(digital)
    if not analog and not digital:
        return
    if not isinstance(simulator, ArduinoBoardSimulator):
        raise TypeError(
            f"--analog and --digital apply to Arduino simulators only, not to "
            f"{type(simulator).__name__}"
        )
    for pin, volts in analog:
        simulator.set_analogue(pin, volts=volts)
    for pin, high in digital:
        simulator.set_input_level(pin, high)

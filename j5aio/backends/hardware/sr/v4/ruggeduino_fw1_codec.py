r"""The SR Ruggeduino single-character protocol, firmware 1: pure encode and parse.

A command is one letter followed by pin letters (pin ``n`` is ``chr(ord("a") + n)``),
with no terminator. After every command the board prints the command's output, if any,
and a ``\n``: ``v`` → ``SRduino:1``, ``r<p>`` → ``h``/``l``, ``a<p>`` → 0…1023, and
an empty line for the mode and write commands.

This module does no I/O: the hardware backend and the Ruggeduino simulator both use it.
"""

from __future__ import annotations

import re
from typing import Final

from j5aio._records import FrozenRecord, frozen_record
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.errors import UnexpectedReplyError

__all__ = [
    "ANALOGUE_CHANNELS",
    "OFFICIAL_FIRMWARE_NAME",
    "SUPPORTED_VERSIONS",
    "VERSION_QUERY",
    "RuggeduinoVersion",
    "decode_pin",
    "encode_analogue_read",
    "encode_command",
    "encode_digital_read",
    "encode_digital_write",
    "encode_mode",
    "encode_pin",
    "parse_analogue",
    "parse_digital",
    "parse_version",
]

#: The version query.
VERSION_QUERY: Final = b"v"
#: The name official SR firmware gives before the ``:`` of its version line.
OFFICIAL_FIRMWARE_NAME: Final = "SRduino"
#: The firmware versions this codec speaks.
SUPPORTED_VERSIONS: Final = ("1",)
#: Analogue channels A0 to A5; pins 14 to 19 are read as channels 0 to 5.
ANALOGUE_CHANNELS: Final = 6

_ADC_READING = re.compile(rb"[0-9]{1,4}")
_FIRST_ANALOGUE_PIN = 14
_ADC_STEPS = 1024
_ADC_REFERENCE = 5.0
_MODE_LETTERS: Final = {
    GPIOPinMode.DIGITAL_INPUT: "i",
    GPIOPinMode.DIGITAL_INPUT_PULLUP: "p",
    GPIOPinMode.DIGITAL_OUTPUT: "o",
}


# (The records here write their own ``__init__`` and take freezing, ``__repr__``, ``__eq__``
# and ``__hash__`` from FrozenRecord, as ``@dataclass(frozen=True)`` would make them: a
# kit with this board makes them at start-up, and making the generated ones costs a
# quarter of a millisecond a class. A test checks them against those.)
@frozen_record
class RuggeduinoVersion(FrozenRecord):
    """The board's version line, split: ``<name>:<version>``."""

    name: str
    version: str

    def __init__(self, name: str, version: str) -> None:
        set_field = object.__setattr__
        set_field(self, "name", name)
        set_field(self, "version", version)

    @property
    def is_official(self) -> bool:
        """Whether the board runs SR's own firmware (custom firmware may answer too)."""
        return self.name == OFFICIAL_FIRMWARE_NAME


def encode_pin(pin: int) -> str:
    """Return the letter for ``pin`` (0 → ``a``, 13 → ``n``, 19 → ``t``).

    :raises ValueError: ``pin`` is outside 0…25.
    """
    if not 0 <= pin < 26:
        raise ValueError(f"a Ruggeduino pin letter encodes 0 to 25, not {pin!r}")
    return chr(ord("a") + pin)


def decode_pin(letter: int) -> int:
    """Return the pin number of a pin byte (``ord("c")`` → 2)."""
    return letter - ord("a")


def encode_command(letter: str, *pins: int) -> bytes:
    """Return a command: the letter followed by the pin letters.

    :raises ValueError: ``letter`` is not exactly one character.
    """
    if len(letter) != 1:
        raise ValueError(f"a Ruggeduino command is one character, not {letter!r}")
    return (letter + "".join(encode_pin(pin) for pin in pins)).encode("ascii")


def encode_mode(pin: int, mode: GPIOPinMode) -> bytes:
    """Return the command that puts ``pin`` in ``mode`` (``i``, ``p`` or ``o``).

    :raises ValueError: ``mode`` is not a digital mode.
    """
    try:
        letter = _MODE_LETTERS[mode]
    except KeyError:
        raise ValueError(
            f"the Ruggeduino protocol sets digital modes only "
            f"({', '.join(m.name for m in _MODE_LETTERS)}), not {mode!r}",
        ) from None
    return encode_command(letter, pin)


def encode_digital_write(pin: int, state: bool) -> bytes:
    """Return the command that drives ``pin`` high (``h``) or low (``l``)."""
    return encode_command("h" if state else "l", pin)


def encode_digital_read(pin: int) -> bytes:
    """Return the command that reads ``pin`` (``r``)."""
    return encode_command("r", pin)


def encode_analogue_read(pin: int) -> bytes:
    """Return the command that reads analogue pin ``pin`` (14…19, sent as channel 0…5).

    :raises ValueError: ``pin`` is not an analogue pin.
    """
    channel = pin - _FIRST_ANALOGUE_PIN
    if channel not in range(ANALOGUE_CHANNELS):
        raise ValueError(f"the Ruggeduino has analogue pins 14 to 19, not {pin!r}")
    return encode_command("a", channel)


def parse_version(line: bytes) -> RuggeduinoVersion:
    """Split the version line (``SRduino:1``) into name and version.

    :raises UnexpectedReplyError: the line has no ``:``.
    """
    text = line.decode("ascii", errors="replace").strip()
    name, separator, _ = text.partition(":")
    if not separator:
        raise UnexpectedReplyError(
            f"expected a Ruggeduino version line like 'SRduino:1', got {text!r}",
        )
    return RuggeduinoVersion(name, text.rsplit(":", 1)[1])


def parse_digital(line: bytes) -> bool:
    """Return the level of a digital read reply (``h`` → True, ``l`` → False).

    :raises UnexpectedReplyError: any other reply.
    """
    if line == b"h":
        return True
    if line == b"l":
        return False
    raise UnexpectedReplyError(f"expected 'h' or 'l' from a Ruggeduino pin read, got {line!r}")


def parse_analogue(line: bytes) -> float:
    """Return the voltage of an analogue read reply: ``value / 1024 x 5``.

    The firmware prints the ADC reading in decimal, with no sign, spaces or padding.

    :raises UnexpectedReplyError: the reply is not such an integer in 0…1023.
    """
    if not _ADC_READING.fullmatch(line) or int(line) >= _ADC_STEPS:
        raise UnexpectedReplyError(
            f"expected a number 0 to 1023 from a Ruggeduino analogue read, got {line!r}",
        )
    value = int(line)
    return value / _ADC_STEPS * _ADC_REFERENCE

r"""The SR Arduino single-character protocol, firmware 2 (``SRduino:2``): pure encode and parse.

Firmware 2 speaks the Ruggeduino protocol of firmware 1 (:mod:`.ruggeduino_fw1_codec`,
whose encoders are reused here) and adds one command: ``u<trigger><echo>`` measures with
an ultrasound sensor and answers the distance in millimetres, ``5 x µs // 29``, or ``0``
when no echo came back within 60 ms. Analogue pins are sent by pin number (``o`` for
A0 … ``t`` for A5), as sr-robot3 does; the firmware takes channel or pin alike.

Every parser accepts exactly what the firmware can send and raises
:class:`~j5aio.errors.UnexpectedReplyError` (naming the reply) for anything else.
This module does no I/O.
"""

from __future__ import annotations

import re
from typing import Final

from j5aio.backends.hardware.sr.v4.ruggeduino_fw1_codec import (
    OFFICIAL_FIRMWARE_NAME,
    VERSION_QUERY,
    RuggeduinoVersion,
    encode_command,
    encode_digital_read,
    encode_digital_write,
    encode_mode,
    parse_digital,
)
from j5aio.errors import UnexpectedReplyError

__all__ = [
    "MAX_ULTRASOUND_MM",
    "OFFICIAL_FIRMWARE_NAME",
    "SUPPORTED_VERSIONS",
    "VERSION_QUERY",
    "RuggeduinoVersion",
    "encode_analogue_read",
    "encode_digital_read",
    "encode_digital_write",
    "encode_mode",
    "encode_ultrasound",
    "parse_analogue",
    "parse_digital",
    "parse_done",
    "parse_empty",
    "parse_ultrasound",
    "parse_version",
]

#: The firmware versions this codec speaks.
SUPPORTED_VERSIONS: Final = ("2",)
#: The longest reading: an echo just inside the 60 ms ``pulseIn`` timeout.
MAX_ULTRASOUND_MM: Final = 5 * 60_000 // 29

_ANALOGUE_PINS: Final = range(14, 20)
_ADC_STEPS: Final = 1024
_ADC_REFERENCE: Final = 5.0
_UNSIGNED: Final = re.compile(rb"0|[1-9][0-9]{0,4}")
_VERSION_FIELD: Final = re.compile(rb"[\x21-\x39\x3b-\x7e]+")  # printable ASCII but ':'


def encode_analogue_read(pin: int) -> bytes:
    """Return the command that reads analogue pin ``pin`` (14…19, sent as ``o``…``t``).

    :raises ValueError: ``pin`` is not an analogue pin.
    """
    if pin not in _ANALOGUE_PINS:
        raise ValueError(f"the SR Arduino has analogue pins 14 to 19, not {pin!r}")
    return encode_command("a", pin)


def encode_ultrasound(trigger: int, echo: int) -> bytes:
    """Return the command that measures with the sensor on ``trigger`` and ``echo``."""
    return encode_command("u", trigger, echo)


def parse_version(line: bytes) -> RuggeduinoVersion:
    """Split the version line (``SRduino:2``) into name and version.

    :raises UnexpectedReplyError: the line is not ``<name>:<version>`` in printable ASCII.
    """
    name, separator, version = line.partition(b":")
    if not (separator and _VERSION_FIELD.fullmatch(name) and _VERSION_FIELD.fullmatch(version)):
        raise UnexpectedReplyError(f"expected a version line like 'SRduino:2', got {line!r}")
    return RuggeduinoVersion(name.decode("ascii"), version.decode("ascii"))


def parse_empty(line: bytes) -> None:
    """Check the reply of a command that prints nothing (a mode or a write): an empty line.

    :raises UnexpectedReplyError: the line is not empty.
    """
    if line:
        raise UnexpectedReplyError(f"expected an empty line, got {line!r}")


#: The reply check of a mode change or a write, by the name backends use.
parse_done = parse_empty


def _parse_unsigned(line: bytes, high: int, what: str) -> int:
    if not _UNSIGNED.fullmatch(line) or int(line) > high:
        raise UnexpectedReplyError(f"expected {what} (0 to {high}), got {line!r}")
    return int(line)


def parse_analogue(line: bytes) -> float:
    """Return the voltage of an analogue read: ``value / 1024 x 5`` volts.

    :raises UnexpectedReplyError: the reply is not a decimal 0…1023.
    """
    return _parse_unsigned(line, _ADC_STEPS - 1, "an ADC reading") / _ADC_STEPS * _ADC_REFERENCE


def parse_ultrasound(line: bytes) -> int:
    """Return the millimetres of a ``u`` reply (0 means no echo).

    :raises UnexpectedReplyError: the reply is not a decimal the firmware can send.
    """
    return _parse_unsigned(line, MAX_ULTRASOUND_MM, "a distance in mm")

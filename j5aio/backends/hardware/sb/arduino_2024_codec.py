r"""The SourceBots Arduino sb2024 colon protocol (firmware ``2.0``): pure encode and parse.

A request is ``:``-separated ASCII ending ``\n`` (the firmware does not strip ``\r``);
every request gets one reply line: ``ACK``, a value, or ``NACK:<reason>``.

=========================================== ===========================================
request                                     reply
=========================================== ===========================================
``*IDN?``                                   ``SourceBots:Arduino:X:2.0``
``*STATUS?``                                ``Yes``
``PIN:<n>:MODE:SET:<mode>``                 ``ACK`` (mode INPUT, INPUT_PULLUP, OUTPUT)
``PIN:<n>:MODE:GET?``                       ``INPUT``, ``INPUT_PULLUP`` or ``OUTPUT``
``PIN:<n>:DIGITAL:SET:<1|0>``               ``ACK``
``PIN:<n>:DIGITAL:GET?``                    ``1`` or ``0``
``PIN:<n>:ANALOG:GET?``                     0…1023
``ULTRASOUND:<trig>:<echo>:MEASURE?``       millimetres, ``5 * µs / 29`` in a 16-bit int
=========================================== ===========================================

The echo time is held in a signed 16-bit ``int``, so an echo longer than 32 767 µs
wraps negative: a reading of 0 or below means "no echo". Every parser here accepts
exactly what the firmware can send and raises
:class:`~j5aio.errors.UnexpectedReplyError` (naming the reply) for anything else.

This module does no I/O.
"""

from __future__ import annotations

import re
from typing import Final

from j5aio._records import FrozenRecord, frozen_record
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.errors import UnexpectedReplyError

__all__ = [
    "ACK",
    "BOARD_TYPE",
    "IDENTIFY",
    "MANUFACTURER",
    "MAX_ULTRASOUND_MM",
    "MIN_ULTRASOUND_MM",
    "STATUS",
    "STATUS_REPLY",
    "SUPPORTED_VERSIONS",
    "Identity",
    "encode_analogue_read",
    "encode_digital_read",
    "encode_digital_write",
    "encode_mode",
    "encode_mode_query",
    "encode_ultrasound",
    "parse_ack",
    "parse_analogue",
    "parse_digital",
    "parse_done",
    "parse_identity",
    "parse_mode",
    "parse_ultrasound",
]

#: The identity query.
IDENTIFY: Final = b"*IDN?\n"
#: The status query: it changes nothing, and only it is answered :data:`STATUS_REPLY`.
STATUS: Final = b"*STATUS?\n"
#: The reply to :data:`STATUS`.
STATUS_REPLY: Final = b"Yes"
#: The manufacturer field of the identity.
MANUFACTURER: Final = "SourceBots"
#: The board-type field of the identity.
BOARD_TYPE: Final = "Arduino"
#: The firmware versions this codec speaks.
SUPPORTED_VERSIONS: Final = ("2.0",)
#: The reply to a command that worked.
ACK: Final = b"ACK"
#: The longest reading the firmware can send: 5 x 32767 // 29.
MAX_ULTRASOUND_MM: Final = 5 * 32767 // 29
#: The most negative reading (an echo that wrapped the 16-bit int), truncated as C does.
MIN_ULTRASOUND_MM: Final = -(5 * 32768 // 29)

_NACK: Final = b"NACK:"
_ADC_STEPS: Final = 1024
_ADC_REFERENCE: Final = 5.0
_MODE_NAMES: Final = {
    GPIOPinMode.DIGITAL_INPUT: "INPUT",
    GPIOPinMode.DIGITAL_INPUT_PULLUP: "INPUT_PULLUP",
    GPIOPinMode.DIGITAL_OUTPUT: "OUTPUT",
}
_MODES_BY_NAME: Final = {name.encode(): mode for mode, name in _MODE_NAMES.items()}
_DECIMAL: Final = re.compile(rb"-?(0|[1-9][0-9]{0,4})")
_FIELD: Final = re.compile(r"[\x20-\x39\x3b-\x7e]+")  # printable ASCII but ':'
_PIN_RANGE: Final = range(0, 20)


# (The records here write their own ``__init__`` and take freezing, ``__repr__``, ``__eq__``
# and ``__hash__`` from FrozenRecord, as ``@dataclass(frozen=True)`` would make them: a
# kit with this board makes them at start-up, and making the generated ones costs a
# quarter of a millisecond a class. A test checks them against those.)
@frozen_record
class Identity(FrozenRecord):
    """The four fields of the ``*IDN?`` reply."""

    manufacturer: str
    board_type: str
    asset_tag: str
    version: str

    def __init__(self, manufacturer: str, board_type: str, asset_tag: str, version: str) -> None:
        set_field = object.__setattr__
        set_field(self, "manufacturer", manufacturer)
        set_field(self, "board_type", board_type)
        set_field(self, "asset_tag", asset_tag)
        set_field(self, "version", version)

    @property
    def is_sb_arduino(self) -> bool:
        """Whether the reply comes from a SourceBots Arduino (of any version)."""
        return self.manufacturer == MANUFACTURER and self.board_type == BOARD_TYPE


def _pin(pin: int) -> int:
    if isinstance(pin, bool) or not isinstance(pin, int) or pin not in _PIN_RANGE:
        raise ValueError(f"a SourceBots Arduino pin is 0 to 19, not {pin!r}")
    return pin


def encode_mode(pin: int, mode: GPIOPinMode) -> bytes:
    """Return the request that puts ``pin`` in a digital ``mode``.

    :raises ValueError: ``mode`` is not INPUT, INPUT_PULLUP or OUTPUT, or ``pin`` is not 0…19.
    """
    try:
        name = _MODE_NAMES[mode]
    except KeyError:
        raise ValueError(
            "the sb2024 firmware sets the modes "
            f"{', '.join(m.name for m in _MODE_NAMES)} only, not {mode!r}",
        ) from None
    return b"PIN:%d:MODE:SET:%s\n" % (_pin(pin), name.encode())


def encode_mode_query(pin: int) -> bytes:
    """Return the request that reads the mode of ``pin``."""
    return b"PIN:%d:MODE:GET?\n" % _pin(pin)


def encode_digital_write(pin: int, level: bool) -> bytes:
    """Return the request that drives ``pin`` high (``1``) or low (``0``)."""
    return b"PIN:%d:DIGITAL:SET:%d\n" % (_pin(pin), 1 if level else 0)


def encode_digital_read(pin: int) -> bytes:
    """Return the request that reads the level of ``pin``."""
    return b"PIN:%d:DIGITAL:GET?\n" % _pin(pin)


def encode_analogue_read(pin: int) -> bytes:
    """Return the request that reads the ADC on ``pin`` (14…19 are A0…A5)."""
    return b"PIN:%d:ANALOG:GET?\n" % _pin(pin)


def encode_ultrasound(trigger: int, echo: int) -> bytes:
    """Return the request that measures a distance with trigger and echo pins."""
    return b"ULTRASOUND:%d:%d:MEASURE?\n" % (_pin(trigger), _pin(echo))


def _refuse(what: str, line: bytes) -> UnexpectedReplyError:
    if line.startswith(_NACK):
        reason = line[len(_NACK) :].decode("ascii", errors="replace")
        return UnexpectedReplyError(f"the board refused the command: NACK {reason!r}")
    return UnexpectedReplyError(f"expected {what}, got {line!r}")


def parse_identity(line: bytes) -> Identity:
    """Split the ``*IDN?`` reply into its four fields.

    :raises UnexpectedReplyError: the reply is not four ``:``-separated printable fields.
    """
    try:
        text = line.decode("ascii")
    except UnicodeDecodeError:
        raise _refuse("an identity like 'SourceBots:Arduino:X:2.0'", line) from None
    fields = text.split(":")
    if len(fields) != 4 or not all(_FIELD.fullmatch(field) for field in fields):
        raise _refuse("an identity like 'SourceBots:Arduino:X:2.0'", line)
    return Identity(*fields)


def parse_ack(line: bytes) -> None:
    """Check that a reply is ``ACK``.

    :raises UnexpectedReplyError: it is a NACK, or anything else.
    """
    if line != ACK:
        raise _refuse("'ACK'", line)


#: The acknowledgement check of a mode change or a write, by the name backends use.
parse_done = parse_ack


def parse_mode(line: bytes) -> GPIOPinMode:
    """Return the mode a ``MODE:GET?`` reply names.

    :raises UnexpectedReplyError: any other reply.
    """
    try:
        return _MODES_BY_NAME[line]
    except KeyError:
        raise _refuse("'INPUT', 'INPUT_PULLUP' or 'OUTPUT'", line) from None


def parse_digital(line: bytes) -> bool:
    """Return the level of a ``DIGITAL:GET?`` reply (``1`` → True, ``0`` → False).

    :raises UnexpectedReplyError: any other reply.
    """
    if line == b"1":
        return True
    if line == b"0":
        return False
    raise _refuse("'1' or '0'", line)


def _parse_int(line: bytes, low: int, high: int, what: str) -> int:
    if not _DECIMAL.fullmatch(line) or line == b"-0":
        raise _refuse(f"{what} ({low} to {high})", line)
    value = int(line)
    if not low <= value <= high:
        raise _refuse(f"{what} ({low} to {high})", line)
    return value


def parse_analogue(line: bytes) -> float:
    """Return the voltage of an ``ANALOG:GET?`` reply: ``value / 1024 x 5`` volts.

    :raises UnexpectedReplyError: the reply is not a decimal 0…1023.
    """
    value = _parse_int(line, 0, _ADC_STEPS - 1, "an ADC reading")
    return value / _ADC_STEPS * _ADC_REFERENCE


def parse_ultrasound(line: bytes) -> int:
    """Return the millimetres of an ``ULTRASOUND`` reply, as the firmware computed them.

    Zero or negative means no echo (a timeout, or an echo that wrapped the 16-bit int).

    :raises UnexpectedReplyError: the reply is not a decimal the firmware can send.
    """
    return _parse_int(line, MIN_ULTRASOUND_MM, MAX_ULTRASOUND_MM, "a distance in mm")

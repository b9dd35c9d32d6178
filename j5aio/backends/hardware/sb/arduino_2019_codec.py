r"""The SourceBots Arduino 2019 line protocol (firmware 2019.6.0 and later): pure encode and parse.

A request is a line, ``<letter> <args…>\n``. The board echoes it as ``# <command>``,
then sends zero or more ``> <data>`` lines and ends with ``+ OK`` or ``- Error…``. On
reset it prints ``# Booted`` and a version line ``# SBDuino GPIO v2019.8.0``.

This module does no I/O: the hardware backend and the SB Arduino simulator both use it.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Final

from j5aio._records import FrozenRecord, frozen_record
from j5aio.backends.hardware.transports import readers
from j5aio.backends.hardware.transports.readers import LinesUntilReader, read_lines_until
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.errors import CommunicationError, UnexpectedReplyError, UnsupportedFirmwareError

if TYPE_CHECKING:
    from j5aio._timedelta import timedelta

__all__ = [
    "ANALOGUE_CHANNELS",
    "BOARD_NAME",
    "BOOT_LINE",
    "MAX_REQUEST_ID",
    "MINIMUM_VERSION",
    "REPLY",
    "SERVO_COUNT",
    "SUPPORTED_VERSIONS",
    "ArduinoError",
    "Reply",
    "check_version",
    "encode_analogue_read",
    "encode_command",
    "encode_digital_read",
    "encode_pin_state",
    "encode_servo",
    "encode_ultrasound",
    "is_final_line",
    "parse_analogue",
    "parse_digital",
    "parse_reply",
    "parse_ultrasound_distance",
    "parse_ultrasound_pulse",
    "parse_version_line",
    "reply_to",
    "servo_level",
    "with_request_id",
]

#: The board's name in errors.
BOARD_NAME: Final = "SourceBots Arduino"
#: The first line the board prints after a reset.
BOOT_LINE: Final = "# Booted"
#: The oldest firmware this codec speaks.
MINIMUM_VERSION: Final = (2019, 6, 0)
#: How the supported versions are described in errors.
SUPPORTED_VERSIONS: Final = ("2019.6.0 or later (three numbers)",)
#: Analogue channels reported by ``A``: A0 to A3.
ANALOGUE_CHANNELS: Final = 4
#: Servo channels of the 2019.6.0 servo shield.
SERVO_COUNT: Final = 16

_FIRST_ANALOGUE_PIN = 14
_ADC_STEPS = 1024
_ADC_REFERENCE = 5.0
_SERVO_MIN = 150
_SERVO_MAX = 550
#: The largest request id (the firmware holds it in a 16-bit signed int; 0 means none).
MAX_REQUEST_ID: Final = 32767


# The numbers in replies are plain ASCII digits, and request ids too: checked with str
# and bytes methods rather than a regular expression each, which a start would compile
# whether it reads them or not.
def _id_prefix_end(line: bytes) -> int:
    """Where ``line``'s request id prefix ends, or 0 if it has none.

    The prefix is ``@``, an optional ``-``, ASCII digits and a space (``@12 ``).
    """
    if not line.startswith(b"@"):
        return 0
    space = line.find(b" ", 1)
    number = line[2:space] if line.startswith(b"@-") else line[1:space]
    return space + 1 if space > 0 and number.isdigit() else 0


def _is_digits(text: str, most: int) -> bool:
    """Whether ``text`` is 1 to ``most`` ASCII digits (no sign, space or point)."""
    return 0 < len(text) <= most and text.isascii() and text.isdigit()


def _is_decimal(text: str, whole: int, fraction: int) -> bool:
    """Whether ``text`` is 1 to ``whole`` digits, then maybe a point and 1 to ``fraction``."""
    head, point, tail = text.partition(".")
    return _is_digits(head, whole) and (not point or _is_digits(tail, fraction))


_UINT16_MAX = 65535
_UINT32_MAX = 2**32 - 1


class ArduinoError(CommunicationError):
    """The Arduino answered a command with ``- Error…``."""


# (It writes its own ``__init__`` and takes freezing, ``__repr__``, ``__eq__`` and
# ``__hash__`` from FrozenRecord, as ``@dataclass(frozen=True)`` would make them: the
# default kit imports it, and making the generated ones costs a quarter of a millisecond.
# A test checks them against those.)
@frozen_record
class Reply(FrozenRecord):
    """A successful reply: the data of its ``>`` lines, in order."""

    data: tuple[str, ...]

    def __init__(self, data: tuple[str, ...]) -> None:
        object.__setattr__(self, "data", data)


def encode_command(letter: str, *args: object, request_id: int | None = None) -> bytes:
    r"""Return the request line: the letter and the arguments, space separated, then ``\n``.

    :param request_id: prefix the request with ``@<request_id>`` and a space (1 to 32767), so that
        its echo and reply lines carry it.
    :raises ValueError: ``letter`` is not exactly one character, or a bad request id.
    """
    if len(letter) != 1:
        raise ValueError(f"an SB Arduino command is one character, not {letter!r}")
    words = [letter, *map(str, args)]
    if request_id is not None:
        if not 1 <= request_id <= MAX_REQUEST_ID:
            raise ValueError(f"a request id is 1 to {MAX_REQUEST_ID}, not {request_id!r}")
        words.insert(0, f"@{request_id}")
    return (" ".join(words) + "\n").encode("ascii")


def with_request_id(request: bytes, request_id: int) -> bytes:
    """Return ``request`` (a line made by an ``encode_`` function) with a request id.

    :raises ValueError: a bad request id, or ``request`` already has one.
    """
    if not 1 <= request_id <= MAX_REQUEST_ID:
        raise ValueError(f"a request id is 1 to {MAX_REQUEST_ID}, not {request_id!r}")
    if request.startswith(b"@"):
        raise ValueError(f"{request!r} already has a request id")
    return b"@%d " % request_id + request


def _strip_id(line: bytes) -> bytes:
    return line[_id_prefix_end(line) :]


def encode_pin_state(pin: int, mode: GPIOPinMode, state: bool) -> bytes:
    """Return the ``W`` request that applies ``mode`` (and, for an output, ``state``).

    ``Z`` is an input, ``P`` an input with pull-up, ``H``/``L`` an output driven high/low.

    :raises ValueError: ``mode`` is not a digital mode.
    """
    if mode is GPIOPinMode.DIGITAL_INPUT:
        letter = "Z"
    elif mode is GPIOPinMode.DIGITAL_INPUT_PULLUP:
        letter = "P"
    elif mode is GPIOPinMode.DIGITAL_OUTPUT:
        letter = "H" if state else "L"
    else:
        raise ValueError(
            "the SB Arduino sets DIGITAL_INPUT, DIGITAL_INPUT_PULLUP or DIGITAL_OUTPUT, "
            f"not {mode!r}",
        )
    return encode_command("W", pin, letter)


def encode_digital_read(pin: int) -> bytes:
    """Return the ``R`` request that reads ``pin``."""
    return encode_command("R", pin)


def encode_analogue_read() -> bytes:
    """Return the ``A`` request, which reads A0 to A3 at once."""
    return encode_command("A")


def encode_ultrasound(trigger: int, echo: int, *, distance: bool) -> bytes:
    """Return the ``U`` (distance in mm) or ``T`` (echo time in µs) request."""
    return encode_command("U" if distance else "T", trigger, echo)


def servo_level(position: float | None) -> int:
    """Return the servo shield's width for ``position``: ``150 + int(400 x (p + 1) / 2)``.

    ``None`` (unpowered) is 0.

    :raises ValueError: ``position`` is outside [-1, 1].
    """
    if position is None:
        return 0
    if not -1 <= position <= 1:
        raise ValueError(f"a servo position must be between -1 and 1, not {position}")
    return _SERVO_MIN + int((_SERVO_MAX - _SERVO_MIN) * (position + 1) / 2)


def encode_servo(servo: int, position: float | None) -> bytes:
    """Return the ``S`` request that moves ``servo`` (firmware 2019.6.0 only)."""
    return encode_command("S", servo, servo_level(position))


def is_final_line(line: bytes) -> bool:
    """Whether ``line`` ends a reply: anything but a ``#`` or ``>`` line or a blank one.

    A reply ends with ``+ OK`` or ``- Error…`` (after any ``@<n>`` request id); any
    other unexpected line ends it too, so that :func:`parse_reply` reports it at once
    rather than after a timeout.
    """
    stripped = _strip_id(line.strip())
    return bool(stripped) and not stripped.startswith((b"#", b">"))


#: The reader of a whole reply (any ``#`` echo, ``>`` data lines, the final line), for a
#: request sent while no other reply can be on its way; see :func:`reply_to` otherwise.
REPLY: Final[LinesUntilReader] = read_lines_until(is_final_line)


def reply_to(request: bytes) -> readers.MatchingReader[list[bytes]]:
    """Return the reader of the reply to ``request``, skipping replies to other requests.

    ``request`` must carry a request id (see :func:`with_request_id`). A reply is taken
    as this request's when its echo line is ``# <request>`` or its final line starts
    with the request's ``@<n>`` prefix; whole replies to other requests are skipped.

    :raises ValueError: ``request`` has no request id.
    """
    line = request.strip()
    end = _id_prefix_end(line)
    if not end:
        raise ValueError(f"{request!r} has no request id; see with_request_id")
    echo = b"# " + b" ".join(line.split())
    prefix = line[:end]

    def answers_request(lines: list[bytes]) -> bool:
        return lines[-1].strip().startswith(prefix) or any(item.strip() == echo for item in lines)

    answers_request.__name__ = f"answers {line.decode('ascii', 'replace')!r}"
    # (looked up on the module: the readers module makes its matching reader on first use)
    return readers.matching(REPLY, answers_request)


def parse_reply(lines: list[bytes]) -> Reply:
    """Return the data of a reply's lines, the final ``+``/``-`` line included.

    ``#`` lines (the echo) are skipped, and ``@<n>`` request ids removed.

    :raises ArduinoError: the board reported an error.
    :raises UnexpectedReplyError: a line that fits no kind of reply line.
    """
    data: list[str] = []
    for raw in lines:
        line = _strip_id(raw.strip()).decode("ascii", errors="replace").strip()
        code, _, rest = line.partition(" ")
        if code in ("#", ""):
            continue
        if code == ">":
            data.append(rest.strip())
        elif code == "+":
            return Reply(tuple(data))
        elif code.startswith("-"):
            raise ArduinoError(f"the {BOARD_NAME} reported an error: {line.lstrip('- ')}")
        else:
            raise UnexpectedReplyError(f"the {BOARD_NAME} sent an unrecognised line: {line!r}")
    raise UnexpectedReplyError(f"the {BOARD_NAME}'s reply has no final '+' or '-' line: {lines!r}")


def _bad(what: str, value: object, expected: str) -> UnexpectedReplyError:
    return UnexpectedReplyError(
        f"the {BOARD_NAME} sent {value!r} as its {what}; expected {expected}",
    )


def _single(reply: Reply, what: str) -> str:
    if len(reply.data) != 1:
        raise UnexpectedReplyError(
            f"expected one '>' line from the {BOARD_NAME} {what}, got {list(reply.data)!r}",
        )
    return reply.data[0]


def parse_digital(reply: Reply) -> bool:
    """Return the level in an ``R`` reply (``H`` → True, ``L`` → False).

    :raises UnexpectedReplyError: not exactly one ``H``/``L`` data line.
    """
    value = _single(reply, "pin read")
    if value == "H":
        return True
    if value == "L":
        return False
    raise UnexpectedReplyError(
        f"expected 'H' or 'L' from the {BOARD_NAME} pin read, got {value!r}",
    )


def parse_analogue(reply: Reply, pin: int) -> float:
    """Return the voltage of analogue ``pin`` (14…17) from an ``A`` reply: ``value / 1024 x 5``.

    Each reading is the decimal ADC value, 0 to 1023, with no sign or padding.

    :raises UnexpectedReplyError: the reply has no line for that channel, or it is malformed.
    """
    wanted = f"a{pin - _FIRST_ANALOGUE_PIN}"
    for item in reply.data:
        name, _, reading = item.partition(" ")
        if name == wanted:
            if not _is_digits(reading, 4) or int(reading) >= _ADC_STEPS:
                raise _bad(f"reading of {wanted}", reading, "a number 0 to 1023")
            return int(reading) / _ADC_STEPS * _ADC_REFERENCE
    raise UnexpectedReplyError(
        f"the {BOARD_NAME}'s analogue reply has no reading for {wanted}: {list(reply.data)!r}",
    )


def parse_ultrasound_pulse(reply: Reply) -> timedelta | None:
    """Return the echo time of a ``T`` reply, or ``None`` when no echo came (0).

    The firmware prints microseconds, optionally with up to two decimals.

    :raises UnexpectedReplyError: the reply is not one such number of 32-bit range.
    """
    value = _single(reply, "ultrasound pulse")
    if not _is_decimal(value, 10, 2) or float(value) > _UINT32_MAX:
        raise _bad("ultrasound pulse", value, "microseconds, 0 to 4294967295")
    microseconds = float(value)
    from j5aio._timedelta import timedelta  # (its C module is loaded at a first reading)

    return None if microseconds == 0 else timedelta(microseconds=microseconds)


def parse_ultrasound_distance(reply: Reply) -> float | None:
    """Return the distance in metres of a ``U`` reply, or ``None`` when no echo came (0).

    The firmware prints whole millimetres, 0 to 65535.

    :raises UnexpectedReplyError: the reply is not one such number.
    """
    value = _single(reply, "ultrasound distance")
    if not _is_digits(value, 5) or int(value) > _UINT16_MAX:
        raise _bad("ultrasound distance", value, "whole millimetres, 0 to 65535")
    millimetres = int(value)
    return None if millimetres == 0 else millimetres / 1000


def parse_version_line(line: bytes) -> str:
    """Return the version in the boot version line: the text after its first ``v``.

    :raises UnexpectedReplyError: the line has no ``v``.
    """
    text = line.decode("ascii", errors="replace").strip()
    _, separator, version = text.partition("v")
    if not separator:
        raise UnexpectedReplyError(
            f"expected a version line like '# SBDuino GPIO v2019.8.0', got {text!r}",
        )
    return version


def check_version(version: str) -> tuple[int, int, int]:
    """Return ``version`` as three numbers if this codec supports it.

    :raises UnsupportedFirmwareError: not three integers, or older than 2019.6.0.
    """
    parts = version.split(".")
    if all(_is_digits(part, 9) for part in parts):
        numbers = tuple(int(part) for part in parts)
    else:
        numbers = ()
    if len(numbers) != 3 or numbers < MINIMUM_VERSION:
        raise UnsupportedFirmwareError(BOARD_NAME, version, SUPPORTED_VERSIONS)
    return numbers[0], numbers[1], numbers[2]

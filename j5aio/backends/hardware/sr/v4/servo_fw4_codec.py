r"""The SR v4 servo board's serial text protocol, firmware 4.3 and the SourceBots 4.4 fork.

The board is a USB CDC serial port (``1BDA:0011``, "Student Robotics" / "Servo Board v4").
Each request is one ``\n``-terminated line and gets exactly one line back: ``ACK`` for
an action, data for a query (its name ends in ``?``), or ``NACK:<reason>``.

``*IDN?`` answers ``Student Robotics:SBv4B:<asset>:<version>``. The version tells the two
firmwares apart (see :data:`FIRMWARES`): SR's 4.3 drives 12 servos with pulses of 500 to
4000 µs, the SourceBots fork 4.4 drives 8 servos with pulses of 300 to 4000 µs. Each kit's
library maps positions -1 to 1 onto its own default pulse limits (sr-robot3: 1000 to
2000 µs; sbot: 350 to 1980 µs), kept here as each firmware's ``default_limits``. Both keep a
pulse in 5 µs ticks, rounded down, so ``SERVO:<n>:GET?`` reads back a multiple of 5 (``0``
for a disabled servo).

Parsing is strict: a reply is accepted only if it is exactly what the firmware can send,
in range; anything else is an :class:`~j5aio.errors.UnexpectedReplyError` naming the
board, the command and the reply. A ``NACK`` is a :class:`~j5aio.errors.CommunicationError`
naming the board, the command and the firmware's reason.

This module does no I/O.
"""

from __future__ import annotations

import re
from typing import Final

from j5aio._records import FrozenRecord, frozen_record
from j5aio.components.pulse_servo import (
    DEFAULT_PULSE_LIMITS,
    PulseLimits,
    position_for_pulse,
    pulse_for_position,
)
from j5aio.errors import CommunicationError, UnexpectedReplyError, UnsupportedFirmwareError

__all__ = [
    "BOARD_TYPE",
    "DEFAULT_PULSE_LIMITS",
    "FIRMWARES",
    "IDENTIFY",
    "MANUFACTURER",
    "PID",
    "PRODUCT",
    "READ_CURRENT",
    "READ_STATUS",
    "READ_VOLTAGE",
    "RESET",
    "SB_DEFAULT_PULSE_LIMITS",
    "TICK_US",
    "VID",
    "Firmware",
    "Identity",
    "Status",
    "check_ack",
    "check_servo",
    "encode_disable",
    "encode_get",
    "encode_set",
    "firmware_for",
    "parse_identity",
    "parse_milli",
    "parse_pulse",
    "parse_status",
    "position_for_pulse",
    "pulse_for_position",
]

#: USB vendor id (University of Southampton).
VID: Final = 0x1BDA
#: USB product id of the servo board (the same as firmware 2, which is not a serial port).
PID: Final = 0x0011
#: The USB manufacturer string.
MANUFACTURER: Final = "Student Robotics"
#: The USB product string.
PRODUCT: Final = "Servo Board v4"
#: The board type in the ``*IDN?`` reply.
BOARD_TYPE: Final = "SBv4B"
#: The length of one firmware tick, in µs: pulses are stored in whole ticks, rounded down.
TICK_US: Final = 5

#: Ask for the identity.
IDENTIFY: Final = b"*IDN?\n"
#: Disable every servo.
RESET: Final = b"*RESET\n"
#: Ask for the watchdog and power-good flags.
READ_STATUS: Final = b"*STATUS?\n"
#: Ask for the servo rail's current, in mA.
READ_CURRENT: Final = b"SERVO:I?\n"
#: Ask for the servo rail's voltage, in mV.
READ_VOLTAGE: Final = b"SERVO:V?\n"

_ACK: Final = b"ACK"
_NACK: Final = b"NACK:"
_DIGITS: Final = re.compile(rb"0|[1-9][0-9]{0,9}")
_VERSION: Final = re.compile(r"[0-9]+(\.[0-9]+)+")
#: The largest meter reading accepted (the firmware's readings are 16-bit).
_MAX_MILLI: Final = 65_535


#: The pulses positions -1 and 1 give on the SourceBots servo board until a program sets
#: its own, in µs: sbot's defaults (its ``START_DUTY_MIN`` and ``START_DUTY_MAX``).
SB_DEFAULT_PULSE_LIMITS: Final[PulseLimits] = (350, 1980)


# (The records here write their own ``__init__`` and take freezing, ``__repr__``, ``__eq__``
# and ``__hash__`` from FrozenRecord, as ``@dataclass(frozen=True)`` would make them: a
# kit with this board makes them at start-up, and making the generated ones costs a
# quarter of a millisecond a class. A test checks them against those.)
@frozen_record
class Firmware(FrozenRecord):
    """What one servo board firmware can do.

    :param version: the version ``*IDN?`` reports.
    :param maker: who builds and ships it.
    :param servo_count: how many servo channels it drives.
    :param min_pulse: the shortest pulse it accepts, in µs.
    :param max_pulse: the longest pulse it accepts, in µs.
    :param default_limits: the pulses positions -1 and 1 give until a program sets its
        own, in µs: the defaults of the kit's own library.
    """

    version: str
    maker: str
    servo_count: int
    min_pulse: int
    max_pulse: int
    default_limits: PulseLimits = DEFAULT_PULSE_LIMITS

    def __init__(
        self,
        version: str,
        maker: str,
        servo_count: int,
        min_pulse: int,
        max_pulse: int,
        default_limits: PulseLimits = DEFAULT_PULSE_LIMITS,
    ) -> None:
        set_field = object.__setattr__
        set_field(self, "version", version)
        set_field(self, "maker", maker)
        set_field(self, "servo_count", servo_count)
        set_field(self, "min_pulse", min_pulse)
        set_field(self, "max_pulse", max_pulse)
        set_field(self, "default_limits", default_limits)


#: The firmwares this codec speaks, by version.
FIRMWARES: Final = {
    "4.3": Firmware(
        "4.3",
        "Student Robotics",
        servo_count=12,
        min_pulse=500,
        max_pulse=4000,
        default_limits=DEFAULT_PULSE_LIMITS,  # sr-robot3's
    ),
    "4.4": Firmware(
        "4.4",
        "SourceBots",
        servo_count=8,
        min_pulse=300,
        max_pulse=4000,
        default_limits=SB_DEFAULT_PULSE_LIMITS,  # sbot's
    ),
}


@frozen_record
class Identity(FrozenRecord):
    """The parts of an ``*IDN?`` reply."""

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


@frozen_record
class Status(FrozenRecord):
    """The parts of a ``*STATUS?`` reply.

    :param watchdog_failed: the I²C link to the pulse expander timed out (usually because
        the board's 12 V supply is missing).
    :param power_good: the servo rail's regulator reports good power.
    """

    watchdog_failed: bool
    power_good: bool

    def __init__(self, watchdog_failed: bool, power_good: bool) -> None:
        set_field = object.__setattr__
        set_field(self, "watchdog_failed", watchdog_failed)
        set_field(self, "power_good", power_good)


def _text(command: bytes) -> str:
    return command.decode("ascii").rstrip("\n")


def _bad(board: str, command: bytes, reply: bytes, why: str) -> UnexpectedReplyError:
    return UnexpectedReplyError(
        f"{board} answered {_text(command)!r} with {reply!r}, {why}",
    )


def _check_not_nack(board: str, command: bytes, reply: bytes) -> None:
    if reply.startswith(_NACK):
        reason = reply[len(_NACK) :].decode("ascii", "replace")
        raise CommunicationError(f"{board} refused {_text(command)!r}: {reason}")


def parse_identity(board: str, reply: bytes) -> Identity:
    """Parse the ``*IDN?`` reply.

    :raises UnexpectedReplyError: not four ``:``-separated ASCII fields, or not a servo
        board (``SBv4B``), or the version is not a dotted number.
    """
    _check_not_nack(board, IDENTIFY, reply)
    try:
        fields = reply.decode("ascii").split(":")
    except UnicodeDecodeError:
        raise _bad(board, IDENTIFY, reply, "which is not ASCII text") from None
    if len(fields) != 4:
        raise _bad(board, IDENTIFY, reply, "not 'Student Robotics:SBv4B:<asset>:<version>'")
    manufacturer, board_type, asset_tag, version = fields
    if board_type != BOARD_TYPE:
        raise _bad(
            board,
            IDENTIFY,
            reply,
            f"so it is a {board_type!r} board, not a servo board ({BOARD_TYPE!r})",
        )
    if not _VERSION.fullmatch(version):
        raise _bad(board, IDENTIFY, reply, f"whose version {version!r} is not a dotted number")
    return Identity(manufacturer, board_type, asset_tag, version)


def firmware_for(board: str, version: str, supported: tuple[str, ...] | None = None) -> Firmware:
    """Return the firmware with ``version``, among ``supported`` (every one by default).

    :raises UnsupportedFirmwareError: naming the version found and those supported.
    """
    allowed = tuple(FIRMWARES) if supported is None else supported
    if version not in allowed:
        raise UnsupportedFirmwareError(board, version, allowed)
    return FIRMWARES[version]


def check_servo(firmware: Firmware, servo: int) -> None:
    """Refuse a servo number that ``firmware`` does not drive.

    :raises TypeError: ``servo`` is not an int.
    :raises ValueError: naming the servos there are.
    """
    if isinstance(servo, bool) or not isinstance(servo, int):
        raise TypeError(f"a servo number must be an int, not {servo!r}")
    if servo not in range(firmware.servo_count):
        raise ValueError(
            f"firmware {firmware.version} has servos 0 to {firmware.servo_count - 1}, not {servo}",
        )


def encode_set(firmware: Firmware, servo: int, pulse_us: int) -> bytes:
    """Return ``SERVO:<n>:SET:<µs>``.

    :raises TypeError: ``servo`` or ``pulse_us`` is not an int.
    :raises ValueError: no such servo, or the pulse is outside the firmware's range.
    """
    check_servo(firmware, servo)
    if isinstance(pulse_us, bool) or not isinstance(pulse_us, int):
        raise TypeError(f"a pulse width must be an int of µs, not {pulse_us!r}")
    if not firmware.min_pulse <= pulse_us <= firmware.max_pulse:
        raise ValueError(
            f"firmware {firmware.version} accepts pulses of {firmware.min_pulse} to "
            f"{firmware.max_pulse} µs, not {pulse_us}",
        )
    return f"SERVO:{servo}:SET:{pulse_us}\n".encode("ascii")


def encode_get(firmware: Firmware, servo: int) -> bytes:
    """Return ``SERVO:<n>:GET?``.

    :raises ValueError: no such servo.
    """
    check_servo(firmware, servo)
    return f"SERVO:{servo}:GET?\n".encode("ascii")


def encode_disable(firmware: Firmware, servo: int) -> bytes:
    """Return ``SERVO:<n>:DISABLE``.

    :raises ValueError: no such servo.
    """
    check_servo(firmware, servo)
    return f"SERVO:{servo}:DISABLE\n".encode("ascii")


def check_ack(board: str, command: bytes, reply: bytes) -> None:
    """Check that an action was acknowledged.

    :raises CommunicationError: the board refused it (``NACK``).
    :raises UnexpectedReplyError: any reply other than ``ACK``.
    """
    if reply == _ACK:
        return
    _check_not_nack(board, command, reply)
    raise _bad(board, command, reply, "not 'ACK'")


def _parse_unsigned(board: str, command: bytes, reply: bytes) -> int:
    _check_not_nack(board, command, reply)
    if not _DIGITS.fullmatch(reply):
        raise _bad(board, command, reply, "not a whole number")
    return int(reply)


def parse_pulse(board: str, command: bytes, reply: bytes, firmware: Firmware) -> int | None:
    """Parse the reply to ``SERVO:<n>:GET?``: the pulse in µs, or ``None`` when disabled.

    :raises UnexpectedReplyError: not ``0`` nor a multiple of 5 within the firmware's range.
    """
    value = _parse_unsigned(board, command, reply)
    if value == 0:
        return None
    if value % TICK_US:
        raise _bad(board, command, reply, f"which is not a whole number of {TICK_US} µs ticks")
    # The firmware's range rounded down to whole ticks.
    low = firmware.min_pulse - firmware.min_pulse % TICK_US
    if not low <= value <= firmware.max_pulse:
        raise _bad(
            board,
            command,
            reply,
            f"outside the {firmware.min_pulse}-{firmware.max_pulse} µs of firmware "
            f"{firmware.version}",
        )
    return value


def parse_milli(board: str, command: bytes, reply: bytes) -> float:
    """Parse a meter reading in mA or mV, and return it in A or V.

    :raises UnexpectedReplyError: not a whole number from 0 to 65535.
    """
    value = _parse_unsigned(board, command, reply)
    if value > _MAX_MILLI:
        raise _bad(board, command, reply, f"more than the meter's {_MAX_MILLI}")
    return value / 1000


def parse_status(board: str, reply: bytes) -> Status:
    """Parse the reply to ``*STATUS?``: ``<watchdog_failed 0/1>:<power_good 0/1>``.

    :raises UnexpectedReplyError: anything else.
    """
    _check_not_nack(board, READ_STATUS, reply)
    fields = reply.split(b":")
    if len(fields) != 2 or any(field not in (b"0", b"1") for field in fields):
        raise _bad(board, READ_STATUS, reply, "not '<0 or 1>:<0 or 1>'")
    return Status(watchdog_failed=fields[0] == b"1", power_good=fields[1] == b"1")

r"""The SR v4 motor board's text protocol, firmware 4.4 / 4.5: pure encode and parse.

The board is a UART at 115 200 baud behind an FTDI FT232R (``0403:6001``, as firmware 3,
which speaks a binary protocol at 1 Mbaud instead). Each command is one ASCII line ending
``\n`` and gets one reply line: ``ACK``, the data asked for, or ``NACK:<reason>``
(:doc:`/internals/sr-motor-board`).

A motor is set with ``MOT:<n>:SET:<v>``, ``v`` from -1000 to 1000: the PWM duty is
``|v| / 1000``, forwards for ``v > 0``; ``v = 0`` *brakes* (driver enabled, both low).
``MOT:<n>:DISABLE`` *coasts* (driver off). A power ``p`` is sent as ``round(p x 1000)``
(half to even); sr-robot3 truncates instead, so the two may differ by one step of 0.1 %.

:data:`IDENTIFY_PROBE` tells this firmware from firmware 3 by what the board answers

This module does no I/O: the hardware backend uses it.
"""

from __future__ import annotations

from typing import Final

from j5aio._records import FrozenRecord, frozen_record
from j5aio.backends.hardware.sr.v4.text_protocol import (
    IDENTIFY,
    Identity,
    check_not_nack,
    command_line,
    parse_flag,
    parse_identity,
    parse_int,
    unexpected_reply,
    version_matches,
)
from j5aio.components.motor import MotorSpecialState, MotorState
from j5aio.errors import UnexpectedReplyError

__all__ = [
    "BAUDRATE",
    "BOARD_TYPE",
    "FULL_SCALE",
    "IDENTIFY",
    "IDENTIFY_PROBE",
    "MOTOR_COUNT",
    "RESET",
    "STATUS",
    "SUPPORTED_VERSIONS",
    "MotorReading",
    "MotorStatus",
    "check_motor",
    "decode_reading",
    "encode_current",
    "encode_get",
    "encode_set",
    "encode_value",
    "is_supported_version",
    "parse_current_ma",
    "parse_identity_reply",
    "parse_reading",
    "parse_status",
]

#: The UART speed of the board, in baud.
BAUDRATE: Final = 115_200
#: The board type field of the identity reply.
BOARD_TYPE: Final = "MCv4B"
#: The firmware versions this codec speaks (SR's 4.4, 4.4.1; SourceBots' 4.5.0).
SUPPORTED_VERSIONS: Final = ("4.4", "4.5")
#: The number of motor channels.
MOTOR_COUNT: Final = 2
#: The wire value of full power.
FULL_SCALE: Final = 1000
#: Ask for the drivers' fault flags and the input voltage.
STATUS: Final = b"*STATUS?\n"
#: Back to the power-on state: both motors coasting, faults cleared.
RESET: Final = b"*RESET\n"
#: What the host sends to find out which firmware answers, safely for both firmwares.
#:
#: ``0x00`` first: firmware 3 takes it as a no-op when idle, and as an ignored speed
#: byte when a previous host died between a motor command and its speed, so no motor
#: moves; every other byte here is ignored by an idle firmware 3, which stays silent.
#: Firmware 4 answers the line ``\x00`` with a NACK, then ``*IDN?`` with its identity.
IDENTIFY_PROBE: Final = b"\x00\n" + IDENTIFY

_MAX_MILLI: Final = 2**31 - 1


# (The records here write their own ``__init__`` and take freezing, ``__repr__``, ``__eq__``
# and ``__hash__`` from FrozenRecord, as ``@dataclass(frozen=True)`` would make them: a
# kit with this board makes them at start-up, and making the generated ones costs a
# quarter of a millisecond a class. A test checks them against those.)
@frozen_record
class MotorReading(FrozenRecord):
    """The reply to ``MOT:<n>:GET?``: whether the driver is enabled, and the value set."""

    enabled: bool
    value: int

    def __init__(self, enabled: bool, value: int) -> None:
        set_field = object.__setattr__
        set_field(self, "enabled", enabled)
        set_field(self, "value", value)


@frozen_record
class MotorStatus(FrozenRecord):
    """The reply to ``*STATUS?``."""

    faults: tuple[bool, ...]
    """Per motor: the driver pulled its enable line low while enabled."""
    input_mv: int
    """The board's input voltage, in mV."""

    def __init__(self, faults: tuple[bool, ...], input_mv: int) -> None:
        set_field = object.__setattr__
        set_field(self, "faults", faults)
        set_field(self, "input_mv", input_mv)


def is_supported_version(version: str) -> bool:
    """Whether this codec speaks firmware ``version`` (4.4, 4.5, with any patch number)."""
    return version_matches(version, SUPPORTED_VERSIONS)


def parse_identity_reply(board: str, reply: bytes) -> Identity:
    """Return the identity in the reply to ``*IDN?``; the board type must be ``MCv4B``.

    :raises UnexpectedReplyError: the reply is not a motor board's identity.
    """
    return parse_identity(board, reply, BOARD_TYPE)


def check_motor(motor: int) -> None:
    """Refuse a number that is not one of the motor board's motors.

    :raises ValueError: naming the motors there are.
    """
    if motor not in range(MOTOR_COUNT):
        raise ValueError(f"the motor board has motors 0 and 1, not {motor!r}")


def encode_value(power: float) -> int:
    """Return the wire value of a power in [-1, 1]: ``round(power x 1000)``.

    :raises TypeError: ``power`` is not a number.
    :raises ValueError: ``power`` is outside [-1, 1].
    """
    if isinstance(power, bool) or not isinstance(power, int | float):
        raise TypeError(f"a motor power must be a float in [-1, 1], not {power!r}")
    if not -1 <= power <= 1:
        raise ValueError(f"a motor power must be between -1 and 1, not {power}")
    return round(power * FULL_SCALE)


def encode_set(motor: int, state: MotorState) -> bytes:
    """Return the command that sets ``motor`` to ``state``.

    A power becomes ``MOT:<n>:SET:<round(p x 1000)>``, BRAKE ``MOT:<n>:SET:0`` and COAST
    ``MOT:<n>:DISABLE``.

    :raises ValueError: no such motor, or a power outside [-1, 1].
    :raises TypeError: ``state`` is neither a number nor a
        :class:`~j5aio.components.motor.MotorSpecialState`.
    """
    # The path of every motor command: checked and formatted here, without calls (the
    # lines are those command_line makes).
    if motor not in range(MOTOR_COUNT):
        raise ValueError(f"the motor board has motors 0 and 1, not {motor!r}")
    if state is MotorSpecialState.COAST:
        return f"MOT:{motor}:DISABLE\n".encode("ascii")
    if state is MotorSpecialState.BRAKE:
        value = 0
    elif type(state) is float and -1.0 <= state <= 1.0:
        value = round(state * FULL_SCALE)
    else:
        value = encode_value(state)  # an int, or bad input (which it refuses)
    return f"MOT:{motor}:SET:{value}\n".encode("ascii")


def encode_get(motor: int) -> bytes:
    """Return the query of ``motor``'s state.

    :raises ValueError: no such motor.
    """
    check_motor(motor)
    return command_line("MOT", motor, "GET?")


def encode_current(motor: int) -> bytes:
    """Return the query of the current ``motor`` draws, in mA.

    :raises ValueError: no such motor.
    """
    check_motor(motor)
    return command_line("MOT", motor, "I?")


def parse_reading(board: str, command: bytes, reply: bytes) -> MotorReading:
    """Return the state in the reply to ``MOT:<n>:GET?``: ``0:0`` or ``1:<-1000..1000>``.

    :raises UnexpectedReplyError: anything else (a disabled motor always reads value 0).
    """
    check_not_nack(board, command, reply)
    enabled_field, separator, value_field = reply.partition(b":")
    expected = "'0:0' (coasting) or '1:<-1000 to 1000>'"
    if not separator:
        raise unexpected_reply(board, command, reply, expected)
    try:
        enabled = parse_flag(board, command, enabled_field)
        value = parse_int(board, command, value_field, low=-FULL_SCALE, high=FULL_SCALE)
    except UnexpectedReplyError:
        raise unexpected_reply(board, command, reply, expected) from None
    if not enabled and value != 0:
        raise unexpected_reply(board, command, reply, expected)
    return MotorReading(enabled, value)


def decode_reading(reading: MotorReading, *, last_set: MotorState | None) -> MotorState:
    """Return the motor state a reading shows.

    Disabled is COAST. Enabled at 0 is a brake, which the board cannot tell from
    power 0.0: it reads as BRAKE unless ``last_set`` (what this host last sent) was a
    power, when it reads as ``0.0``. Any other value is ``value / 1000``.
    """
    if not reading.enabled:
        return MotorSpecialState.COAST
    if reading.value == 0:
        if isinstance(last_set, float | int) and not isinstance(last_set, bool):
            return 0.0
        return MotorSpecialState.BRAKE
    return reading.value / FULL_SCALE


def parse_current_ma(board: str, command: bytes, reply: bytes) -> int:
    """Return the current in the reply to ``MOT:<n>:I?``, in mA (never negative)."""
    return parse_int(board, command, reply, low=0, high=_MAX_MILLI)


def parse_status(board: str, reply: bytes) -> MotorStatus:
    """Return the status in the reply to ``*STATUS?``: ``<fault0>,<fault1>:<input mV>``."""
    check_not_nack(board, STATUS, reply)
    expected = "'<fault 0/1>,<fault 0/1>:<input mV>'"
    faults, separator, millivolts = reply.partition(b":")
    flags = faults.split(b",")
    if not separator or len(flags) != MOTOR_COUNT or any(f not in (b"0", b"1") for f in flags):
        raise unexpected_reply(board, STATUS, reply, expected)
    try:
        input_mv = parse_int(board, STATUS, millivolts, low=0, high=_MAX_MILLI)
    except UnexpectedReplyError:
        raise unexpected_reply(board, STATUS, reply, expected) from None
    return MotorStatus(tuple(flag == b"1" for flag in flags), input_mv)

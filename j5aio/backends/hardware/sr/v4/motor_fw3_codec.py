"""The SR v4 motor board's binary protocol, firmware 3 (1 Mbaud): pure encode and parse.

The host sends raw bytes; the board answers only the version query. A motor command is
two bytes, ``[0x02 + motor, speed]``, where the speed byte ``b`` means ``b - 128``:
``1`` coasts, ``2`` brakes, ``3``…``255`` drive (duty saturates at ``|b - 128| >= 100``),
and ``0`` is ignored. A lone ``0x00`` is ignored when the board is idle and swallowed as
a discarded speed when it is waiting for one, so it resynchronises the board's parser.

This module does no I/O: the hardware backend and the motor board simulator both use it.
"""

from __future__ import annotations

import re
from typing import Final

from j5aio.components.motor import MotorSpecialState, MotorState
from j5aio.errors import UnexpectedReplyError

__all__ = [
    "BAUDRATE",
    "CMD_BOOTLOADER",
    "CMD_MOTOR",
    "CMD_RESYNC",
    "CMD_VERSION",
    "MODEL",
    "MOTOR_COUNT",
    "RESYNC_AND_VERSION_QUERY",
    "SPEED_BRAKE",
    "SPEED_COAST",
    "SPEED_IGNORED",
    "SUPPORTED_VERSIONS",
    "decode_speed",
    "encode_motor_command",
    "encode_speed",
    "encode_version_reply",
    "parse_version_reply",
]

#: The UART speed of the board, in baud.
BAUDRATE: Final = 1_000_000
#: Ignored when idle; discards a half-sent speed command otherwise.
CMD_RESYNC: Final = 0x00
#: Asks for the version line, ``MCV4B:3\n``.
CMD_VERSION: Final = 0x01
#: The command byte that sets the speed of motor 0 and of motor 1.
CMD_MOTOR: Final = (0x02, 0x03)
#: Reboots into the ROM bootloader (never sent by j5aio).
CMD_BOOTLOADER: Final = 0x04
#: The speed byte that the firmware ignores.
SPEED_IGNORED: Final = 0
#: The speed byte that lets the motor spin freely.
SPEED_COAST: Final = 1
#: The speed byte that shorts the motor's terminals.
SPEED_BRAKE: Final = 2
#: The model field of the version reply.
MODEL: Final = "MCV4B"
#: The firmware versions this codec speaks.
SUPPORTED_VERSIONS: Final = ("3",)
#: The number of motor channels.
MOTOR_COUNT: Final = 2
#: What the host sends to ask for the version, resynchronising the parser first.
RESYNC_AND_VERSION_QUERY: Final = bytes((CMD_RESYNC, CMD_VERSION))

_VERSION = re.compile(r"[0-9]{1,5}")
_SCALE = 125
_OFFSET = 128


def encode_speed(state: MotorState) -> int:
    """Return the speed byte for ``state``.

    A power ``p`` becomes ``round(p x 125) + 128`` (Python's round, half to even, as j5),
    so 1.0 → 253, 0.0 → 128, -1.0 → 3.

    :raises ValueError: a power outside [-1, 1].
    :raises TypeError: ``state`` is neither a number nor a :class:`MotorSpecialState`.
    """
    if state is MotorSpecialState.BRAKE:
        return SPEED_BRAKE
    if state is MotorSpecialState.COAST:
        return SPEED_COAST
    if isinstance(state, bool) or not isinstance(state, int | float):
        raise TypeError(
            f"a motor state must be a float in [-1, 1] or a MotorSpecialState, not {state!r}",
        )
    if not -1 <= state <= 1:
        raise ValueError(f"a motor power must be between -1 and 1, not {state}")
    return round(state * _SCALE) + _OFFSET


def decode_speed(speed: int) -> MotorState | None:
    """Return the state a speed byte asks for, or ``None`` for the ignored byte 0.

    Drive bytes decode to ``(speed - 128) / 125``, the inverse of :func:`encode_speed`.

    :raises ValueError: ``speed`` is not a byte.
    """
    if not 0 <= speed <= 0xFF:
        raise ValueError(f"a speed byte must be in 0..255, not {speed}")
    if speed == SPEED_IGNORED:
        return None
    if speed == SPEED_COAST:
        return MotorSpecialState.COAST
    if speed == SPEED_BRAKE:
        return MotorSpecialState.BRAKE
    return (speed - _OFFSET) / _SCALE


def encode_motor_command(motor: int, state: MotorState) -> bytes:
    """Return the two bytes that set ``motor`` (0 or 1) to ``state``.

    :raises ValueError: no such motor, or a power outside [-1, 1].
    """
    if motor not in range(MOTOR_COUNT):
        raise ValueError(f"the motor board has motors 0 and 1, not {motor!r}")
    return bytes((CMD_MOTOR[motor], encode_speed(state)))


def encode_version_reply(version: str = "3") -> bytes:
    r"""Return the version line the board sends, e.g. ``b"MCV4B:3\n"``."""
    return f"{MODEL}:{version}\n".encode("ascii")


def parse_version_reply(line: bytes) -> str:
    """Return the firmware version from the version line (without its line ending).

    :raises UnexpectedReplyError: the line is not ``MCV4B:<version>``, the version
        being a whole number.
    """
    text = line.decode("ascii", errors="replace").rstrip("\r\n")
    model, separator, version = text.partition(":")
    if model != MODEL or not separator or not _VERSION.fullmatch(version):
        raise UnexpectedReplyError(
            f"expected a motor board version line like '{MODEL}:3', got {text!r}; is this "
            "port really an SR v4 motor board?",
        )
    return version

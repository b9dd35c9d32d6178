"""The SR v4 motor board's binary protocol, firmware 3 (1 Mbaud): pure encode and parse.

The host sends raw bytes; the board answers only the version query. A motor command is
two bytes, ``[0x02 + motor, speed]``, where the speed byte ``b`` means ``b - 128``:
``1`` coasts, ``2`` brakes, ``3``…``255`` drive (duty saturates at ``|b - 128| >= 100``),
and ``0`` is ignored. A lone ``0x00`` is ignored when the board is idle and swallowed as
a discarded speed when it is waiting for one, so it resynchronises the board's parser.

A power ``p`` is sent as ``round(p x 100) + 128`` (:data:`LINEAR_SCALE`), so the duty
the board drives is ``|p|``, in steps of 1 %. j5 sent ``round(p x 125) + 128``
(:data:`J5_SCALE`), which saturates from ``|p| = 0.8``; the functions take ``scale`` to
send j5's bytes for a robot tuned against j5.

This module does no I/O: the hardware backend and the motor board simulator both use it.
"""

from __future__ import annotations

from typing import Final

from j5aio.components.motor import MotorSpecialState, MotorState
from j5aio.errors import UnexpectedReplyError

__all__ = [
    "BAUDRATE",
    "CMD_BOOTLOADER",
    "CMD_MOTOR",
    "CMD_RESYNC",
    "CMD_VERSION",
    "J5_SCALE",
    "LINEAR_SCALE",
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


def _is_version(text: str) -> bool:
    """Whether ``text`` is a version as the firmware writes it: 1 to 5 ASCII digits."""
    return 0 < len(text) <= 5 and text.isascii() and text.isdigit()


#: Speed steps per unit of power that make the duty equal the power (1.0 → 100 %).
LINEAR_SCALE: Final = 100
#: j5's speed steps per unit of power: byte-compatible with j5, saturating from 0.8.
J5_SCALE: Final = 125
_OFFSET = 128


def _check_scale(scale: int) -> int:
    if scale not in (LINEAR_SCALE, J5_SCALE):
        raise ValueError(
            f"the speed scale must be LINEAR_SCALE ({LINEAR_SCALE}) or J5_SCALE ({J5_SCALE}), "
            f"not {scale!r}",
        )
    return scale


def encode_speed(state: MotorState, *, scale: int = LINEAR_SCALE) -> int:
    """Return the speed byte for ``state``.

    A power ``p`` becomes ``round(p x scale) + 128`` (Python's round, half to even, as
    j5): with the default linear scale 1.0 → 228, 0.0 → 128, -1.0 → 28, the duty
    being ``|p|``; with :data:`J5_SCALE` 1.0 → 253 and -1.0 → 3, as j5 sent.

    :raises ValueError: a power outside [-1, 1].
    :raises TypeError: ``state`` is neither a number nor a
        :class:`~j5aio.components.motor.MotorSpecialState`.
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
    return round(state * _check_scale(scale)) + _OFFSET


def decode_speed(speed: int, *, scale: int = LINEAR_SCALE) -> MotorState | None:
    """Return the state a speed byte asks for, or ``None`` for the ignored byte 0.

    Drive bytes decode to ``(speed - 128) / scale``, the inverse of :func:`encode_speed`.

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
    return (speed - _OFFSET) / _check_scale(scale)


def encode_motor_command(motor: int, state: MotorState, *, scale: int = LINEAR_SCALE) -> bytes:
    """Return the two bytes that set ``motor`` (0 or 1) to ``state``.

    :param scale: :data:`LINEAR_SCALE` (duty = power) or :data:`J5_SCALE` (j5's bytes).
    :raises ValueError: no such motor, or a power outside [-1, 1].
    """
    if motor not in range(MOTOR_COUNT):
        raise ValueError(f"the motor board has motors 0 and 1, not {motor!r}")
    if type(state) is float and -1.0 <= state <= 1.0 and scale in (LINEAR_SCALE, J5_SCALE):
        # A power (the common case), encoded here without a call, as encode_speed does.
        return bytes((CMD_MOTOR[motor], round(state * scale) + _OFFSET))
    return bytes((CMD_MOTOR[motor], encode_speed(state, scale=scale)))


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
    if model != MODEL or not separator or not _is_version(version):
        raise UnexpectedReplyError(
            f"expected a motor board version line like '{MODEL}:3', got {text!r}; is this "
            "port really an SR v4 motor board?",
        )
    return version

"""The SR v4 servo board's USB control-transfer protocol, firmware 2: pure encode and parse.

Same transfer convention as the firmware 3 power board (``bRequest`` 64, command in
``wIndex``). ``wIndex`` 9 reads the version, 12 starts the pulse generator, and 0 to 11
set a servo's position, a signed 16-bit ``wValue`` in -100…100 sent as its two's
complement.

This module does no I/O: the hardware backend and the servo board simulator both use it.
"""

from __future__ import annotations

from typing import Final

from j5aio.backends.hardware.sr.v4.power_fw3_codec import ReadCommand, parse_u32

__all__ = [
    "FIRMWARE_VERSION",
    "INIT_WRITE",
    "PID",
    "SERVO_COUNT",
    "SUPPORTED_VERSIONS",
    "VID",
    "decode_position",
    "encode_position",
    "parse_u32",
    "servo_write_index",
]

#: USB vendor id (University of Southampton).
VID: Final = 0x1BDA
#: USB product id of the servo board.
PID: Final = 0x0011
#: The firmware version, ``<I``.
FIRMWARE_VERSION: Final = ReadCommand(9, 4)
#: ``wIndex`` of the write that initialises the I²C expander and starts the pulses.
INIT_WRITE: Final = 12
#: The number of servo channels.
SERVO_COUNT: Final = 12
#: The firmware versions this codec speaks.
SUPPORTED_VERSIONS: Final = ("2",)

_SCALE = 100


def servo_write_index(servo: int) -> int:
    """Return the ``wIndex`` that sets ``servo`` (0 to 11).

    :raises ValueError: no such servo (``bool`` is refused too).
    """
    if isinstance(servo, bool) or not isinstance(servo, int) or servo not in range(SERVO_COUNT):
        raise ValueError(f"the servo board has servos 0 to 11 (integers), not {servo!r}")
    return servo


def encode_position(position: float) -> int:
    """Return the ``wValue`` for ``position`` in [-1, 1]: ``round(p x 100)``, half to even.

    Negative values are returned as their 16-bit two's complement (-100 → 0xFF9C).

    :raises ValueError: ``position`` is outside [-1, 1].
    """
    if not -1 <= position <= 1:
        raise ValueError(f"a servo position must be between -1 and 1, not {position}")
    return round(position * _SCALE) & 0xFFFF


def decode_position(w_value: int) -> int:
    """Return the signed position (as the firmware sees it) of a 16-bit ``wValue``."""
    w_value &= 0xFFFF
    return w_value - 0x10000 if w_value & 0x8000 else w_value

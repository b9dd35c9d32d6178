"""Number handling of the Arduino AVR core, which text firmwares inherit.

- ``String::toInt()`` is avr-libc ``atol``: skip leading white space, an optional sign,
  then decimal digits up to the first other character; no digits gives 0; overflow is not
  detected (modelled as wrapping to 32 bits).
- Storing that ``long`` in an ``int`` keeps the low 16 bits (``int`` is 16-bit on AVR).
- ``float`` and ``double`` are both IEEE single precision on AVR.
- ``String(float)`` prints two decimals (``dtostrf``).
"""

from __future__ import annotations

import struct
from typing import Final

__all__ = ["WHITE_SPACE", "float32", "format_float", "to_int16", "to_long"]

#: The bytes C ``isspace`` accepts, which ``atol`` skips and ``String::trim()`` removes.
WHITE_SPACE: Final = b" \t\n\v\f\r"
_SINGLE: Final = struct.Struct("<f")


def _wrap(value: int, bits: int) -> int:
    value &= (1 << bits) - 1
    return value - (1 << bits) if value >> (bits - 1) else value


def to_long(text: bytes) -> int:
    """``String::toInt()``: the leading decimal number of ``text`` as a 32-bit ``long``."""
    stripped = text.lstrip(WHITE_SPACE)
    sign = 1
    if stripped[:1] in (b"+", b"-"):
        sign = -1 if stripped[:1] == b"-" else 1
        stripped = stripped[1:]
    value = 0
    for byte in stripped:
        if not 0x30 <= byte <= 0x39:
            break
        value = value * 10 + byte - 0x30
    return _wrap(sign * value, 32)


def to_int16(value: int) -> int:
    """Store ``value`` in a 16-bit AVR ``int``."""
    return _wrap(value, 16)


def float32(value: float) -> float:
    """Round ``value`` to IEEE single precision."""
    rounded: float = _SINGLE.unpack(_SINGLE.pack(value))[0]
    return rounded


def format_float(value: float) -> bytes:
    """``String(float)``: the value with two decimals."""
    return f"{value:.2f}".encode("ascii")

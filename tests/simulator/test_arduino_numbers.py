from __future__ import annotations

import pytest

from j5aio.simulator.arduino_numbers import float32, format_float, to_int16, to_long


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        (b"42", 42),
        (b"  42abc", 42),
        (b"\t7", 7),
        (b"-7", -7),
        (b"+3", 3),
        (b"", 0),
        (b"abc", 0),
        (b"-", 0),
        (b"12 34", 12),
        (b"4294967297", 1),  # overflow wraps to 32 bits
        (b"2147483648", -2147483648),
    ],
)
def test_to_long_is_atol(text: bytes, expected: int) -> None:
    assert to_long(text) == expected


@pytest.mark.parametrize(
    ("value", "expected"),
    [(2, 2), (65538, 2), (40000, -25536), (-1, -1), (32767, 32767), (32768, -32768)],
)
def test_to_int16_keeps_the_low_16_bits(value: int, expected: int) -> None:
    assert to_int16(value) == expected


def test_float32_rounds_to_single_precision() -> None:
    assert float32(0.1715) == 0.17149999737739563
    assert float32(7173.0) == 7173.0
    assert float32(16777217.0) == 16777216.0


def test_format_float_prints_two_decimals() -> None:
    assert format_float(2345.0) == b"2345.00"
    assert format_float(0.0) == b"0.00"

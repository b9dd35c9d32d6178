"""Every codec's parsers, fed arbitrary bytes: a value in range, or CommunicationError."""

from __future__ import annotations

import contextlib

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from j5aio.backends.hardware.sr.v4 import motor_fw3_codec as motor
from j5aio.backends.hardware.sr.v4 import power_fw3_codec as power
from j5aio.backends.hardware.sr.v4 import ruggeduino_fw1_codec as ruggeduino
from j5aio.backends.hardware.sr.v4 import servo_fw2_codec as servo
from j5aio.errors import CommunicationError

FUZZ = settings(max_examples=400, deadline=None)


@FUZZ
@given(st.binary(max_size=24))
def test_ruggeduino_parsers(data: bytes) -> None:
    with contextlib.suppress(CommunicationError):
        assert 0 <= ruggeduino.parse_analogue(data) < 5
    with contextlib.suppress(CommunicationError):
        assert ruggeduino.parse_digital(data) in (True, False)
    with contextlib.suppress(CommunicationError):
        version = ruggeduino.parse_version(data)
        assert isinstance(version.version, str)


@pytest.mark.parametrize("line", [b" 12 ", b"1_000", b"+5", b"-1", b"1024", b"12\x00", b"\xd9\xa1"])
def test_ruggeduino_analogue_refuses_what_the_firmware_cannot_send(line: bytes) -> None:
    with pytest.raises(CommunicationError, match="Ruggeduino analogue read"):
        ruggeduino.parse_analogue(line)


@FUZZ
@given(st.binary(max_size=24))
def test_motor_version_parser(data: bytes) -> None:
    with contextlib.suppress(CommunicationError):
        version = motor.parse_version_reply(data)
        assert version.isdigit() and version.isascii()


@pytest.mark.parametrize("line", [b"MCV4B:", b"MCV4B:3.0", b"MCV4B: 3", b"MCV4B:+3", b"MCV4B:\xff"])
def test_motor_version_refuses_what_the_firmware_cannot_send(line: bytes) -> None:
    with pytest.raises(CommunicationError, match="motor board version line"):
        motor.parse_version_reply(line)


@FUZZ
@given(st.binary(max_size=12))
def test_power_and_servo_parsers(data: bytes) -> None:
    with contextlib.suppress(CommunicationError):
        assert 0 <= power.parse_u32(data) < 2**32
        assert len(data) == 4
    with contextlib.suppress(CommunicationError):
        reading = power.parse_battery(data)
        assert len(data) == 8
        assert reading.current >= 0 and reading.voltage >= 0
    with contextlib.suppress(CommunicationError):
        assert 0 <= servo.parse_u32(data) < 2**32

"""The sb2024 codec: exact requests, and replies parsed strictly."""

from __future__ import annotations

import contextlib
import re

import pytest
from hypothesis import given
from hypothesis import strategies as st

from j5aio.backends.hardware.sb import arduino_2024_codec as codec
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.errors import UnexpectedReplyError
from tests.dataclass_twins import assert_like_generated


def test_requests() -> None:
    assert codec.IDENTIFY == b"*IDN?\n"
    assert codec.encode_mode(3, GPIOPinMode.DIGITAL_INPUT) == b"PIN:3:MODE:SET:INPUT\n"
    assert codec.encode_mode(19, GPIOPinMode.DIGITAL_INPUT_PULLUP) == (
        b"PIN:19:MODE:SET:INPUT_PULLUP\n"
    )
    assert codec.encode_mode(2, GPIOPinMode.DIGITAL_OUTPUT) == b"PIN:2:MODE:SET:OUTPUT\n"
    assert codec.encode_mode_query(7) == b"PIN:7:MODE:GET?\n"
    assert codec.encode_digital_write(13, True) == b"PIN:13:DIGITAL:SET:1\n"
    assert codec.encode_digital_write(13, False) == b"PIN:13:DIGITAL:SET:0\n"
    assert codec.encode_digital_read(4) == b"PIN:4:DIGITAL:GET?\n"
    assert codec.encode_analogue_read(14) == b"PIN:14:ANALOG:GET?\n"
    assert codec.encode_ultrasound(5, 6) == b"ULTRASOUND:5:6:MEASURE?\n"


@pytest.mark.parametrize("mode", [GPIOPinMode.ANALOGUE_INPUT, GPIOPinMode.PWM_OUTPUT])
def test_modes_the_firmware_lacks(mode: GPIOPinMode) -> None:
    with pytest.raises(ValueError, match="INPUT"):
        codec.encode_mode(3, mode)


@pytest.mark.parametrize("pin", [-1, 20, True, 2.0])
def test_pins_outside_the_protocol(pin: object) -> None:
    with pytest.raises(ValueError, match="0 to 19"):
        codec.encode_digital_read(pin)  # type: ignore[arg-type]


def test_identity() -> None:
    identity = codec.parse_identity(b"SourceBots:Arduino:X:2.0")
    assert identity == codec.Identity("SourceBots", "Arduino", "X", "2.0")
    assert identity.is_sb_arduino
    assert not codec.parse_identity(b"Student_Robotics:PBv4B:sr1:4.4").is_sb_arduino


@pytest.mark.parametrize(
    "line",
    [
        b"",
        b"SourceBots:Arduino:X",
        b"SourceBots:Arduino:X:2.0:extra",
        b"a::b:c",
        b"SourceBots:Arduino:X:2.0\r",
        b"Source\xffBots:Arduino:X:2.0",
        b"NACK:Invalid command",
    ],
)
def test_bad_identities(line: bytes) -> None:
    with pytest.raises(UnexpectedReplyError, match=r"SourceBots:Arduino:X:2\.0|NACK"):
        codec.parse_identity(line)


def test_values() -> None:
    codec.parse_ack(b"ACK")
    assert codec.parse_mode(b"INPUT") is GPIOPinMode.DIGITAL_INPUT
    assert codec.parse_mode(b"INPUT_PULLUP") is GPIOPinMode.DIGITAL_INPUT_PULLUP
    assert codec.parse_mode(b"OUTPUT") is GPIOPinMode.DIGITAL_OUTPUT
    assert codec.parse_digital(b"1") is True
    assert codec.parse_digital(b"0") is False
    assert codec.parse_analogue(b"0") == 0.0
    assert codec.parse_analogue(b"512") == 2.5
    assert codec.parse_analogue(b"1023") == pytest.approx(4.995, abs=1e-3)
    assert codec.parse_ultrasound(b"1000") == 1000
    assert codec.parse_ultrasound(b"0") == 0
    assert codec.parse_ultrasound(b"-954") == -954
    assert codec.parse_ultrasound(b"5649") == codec.MAX_ULTRASOUND_MM == 5649
    assert codec.parse_ultrasound(b"-5649") == codec.MIN_ULTRASOUND_MM == -5649


def test_a_nack_is_named() -> None:
    with pytest.raises(UnexpectedReplyError, match=r"refused.*Invalid command"):
        codec.parse_ack(b"NACK:Invalid command")
    with pytest.raises(UnexpectedReplyError, match=r"refused.*Reset not supported"):
        codec.parse_digital(b"NACK:Reset not supported")


@pytest.mark.parametrize(
    ("parse", "line"),
    [
        (codec.parse_ack, b"ack"),
        (codec.parse_ack, b"ACK "),
        (codec.parse_mode, b"ANALOG"),
        (codec.parse_digital, b"2"),
        (codec.parse_digital, b""),
        (codec.parse_analogue, b"1024"),
        (codec.parse_analogue, b"-1"),
        (codec.parse_analogue, b"+5"),
        (codec.parse_analogue, b"05"),
        (codec.parse_analogue, b"1_0"),
        (codec.parse_analogue, b" 5"),
        (codec.parse_analogue, "٣".encode()),
        (codec.parse_ultrasound, b"5650"),
        (codec.parse_ultrasound, b"-5650"),
        (codec.parse_ultrasound, b"-0"),
        (codec.parse_ultrasound, b"1.5"),
    ],
)
def test_replies_the_firmware_cannot_send(parse: object, line: bytes) -> None:
    with pytest.raises(UnexpectedReplyError, match=re.escape(repr(line))):
        parse(line)  # type: ignore[operator]


@given(st.binary(max_size=40))
def test_arbitrary_bytes_parse_or_raise_unexpected_reply(line: bytes) -> None:
    for parse in (codec.parse_ack, codec.parse_mode, codec.parse_digital, codec.parse_identity):
        with contextlib.suppress(UnexpectedReplyError):
            parse(line)
    try:
        volts = codec.parse_analogue(line)
    except UnexpectedReplyError:
        pass
    else:
        assert 0.0 <= volts < 5.0
        assert line == str(int(line)).encode()
    try:
        millimetres = codec.parse_ultrasound(line)
    except UnexpectedReplyError:
        pass
    else:
        assert codec.MIN_ULTRASOUND_MM <= millimetres <= codec.MAX_ULTRASOUND_MM
        assert line == str(millimetres).encode()


def test_the_identity_is_the_generated_dataclass() -> None:
    assert_like_generated(
        codec.Identity,
        [
            ((codec.MANUFACTURER, codec.BOARD_TYPE, "sbABC", "2024.0.0"), {}),
            ((), {"manufacturer": "m", "board_type": "b", "asset_tag": "", "version": "v"}),
        ],
    )
    assert codec.Identity(codec.MANUFACTURER, codec.BOARD_TYPE, "a", "v").is_sb_arduino
    assert not codec.Identity("m", codec.BOARD_TYPE, "a", "v").is_sb_arduino

"""The SR Arduino firmware 2 codec: fw 1's commands plus ``u``, replies parsed strictly."""

from __future__ import annotations

import contextlib
import re

import pytest
from hypothesis import given
from hypothesis import strategies as st

from j5aio.backends.hardware.sr.v4 import arduino_fw2_codec as codec
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.errors import UnexpectedReplyError


def test_requests() -> None:
    assert codec.VERSION_QUERY == b"v"
    assert codec.encode_mode(14, GPIOPinMode.DIGITAL_OUTPUT) == b"oo"
    assert codec.encode_mode(2, GPIOPinMode.DIGITAL_INPUT_PULLUP) == b"pc"
    assert codec.encode_digital_write(19, True) == b"ht"
    assert codec.encode_digital_read(13) == b"rn"
    assert codec.encode_analogue_read(14) == b"ao"
    assert codec.encode_analogue_read(19) == b"at"
    assert codec.encode_ultrasound(2, 3) == b"ucd"


@pytest.mark.parametrize("pin", [13, 20])
def test_analogue_reads_only_on_a0_to_a5(pin: int) -> None:
    with pytest.raises(ValueError, match="14 to 19"):
        codec.encode_analogue_read(pin)


def test_version() -> None:
    version = codec.parse_version(b"SRduino:2")
    assert (version.name, version.version, version.is_official) == ("SRduino", "2", True)
    assert not codec.parse_version(b"TeamBot:2").is_official


@pytest.mark.parametrize(
    "line", [b"", b"SRduino", b"SRduino:", b":2", b"SRduino:2:3", b"SR duino:2", b"SRduino:\xff"],
)
def test_bad_version_lines(line: bytes) -> None:
    with pytest.raises(UnexpectedReplyError, match="SRduino:2"):
        codec.parse_version(line)


def test_values() -> None:
    codec.parse_empty(b"")
    assert codec.parse_digital(b"h") is True
    assert codec.parse_digital(b"l") is False
    assert codec.parse_analogue(b"256") == 1.25
    assert codec.parse_ultrasound(b"0") == 0
    assert codec.parse_ultrasound(b"1230") == 1230
    assert codec.parse_ultrasound(b"10344") == codec.MAX_ULTRASOUND_MM == 10344


@pytest.mark.parametrize(
    ("parse", "line"),
    [(codec.parse_empty, b"h"), (codec.parse_analogue, b"1024"), (codec.parse_analogue, b"007"),
     (codec.parse_analogue, b"-1"), (codec.parse_ultrasound, b"10345"),
     (codec.parse_ultrasound, b"-5"), (codec.parse_ultrasound, b"12a")],
)
def test_replies_the_firmware_cannot_send(parse: object, line: bytes) -> None:
    with pytest.raises(UnexpectedReplyError, match=re.escape(repr(line))):
        parse(line)  # type: ignore[operator]


@given(st.binary(max_size=30))
def test_arbitrary_bytes_parse_or_raise_unexpected_reply(line: bytes) -> None:
    for parse in (codec.parse_empty, codec.parse_digital, codec.parse_version):
        with contextlib.suppress(UnexpectedReplyError):
            parse(line)
    for parse_number, high in ((codec.parse_analogue, 5.0), (codec.parse_ultrasound, 10344)):
        try:
            value = parse_number(line)
        except UnexpectedReplyError:
            continue
        assert 0 <= value <= high
        assert line == str(int(line)).encode()

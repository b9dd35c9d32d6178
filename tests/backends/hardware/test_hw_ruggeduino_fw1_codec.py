import pytest

from j5aio.backends.hardware.sr.v4 import ruggeduino_fw1_codec as codec
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.errors import UnexpectedReplyError
from tests.dataclass_twins import assert_like_generated


def test_pin_letters() -> None:
    assert codec.encode_pin(0) == "a"
    assert codec.encode_pin(2) == "c"
    assert codec.encode_pin(13) == "n"
    assert codec.encode_pin(19) == "t"
    assert codec.decode_pin(ord("c")) == 2
    with pytest.raises(ValueError, match="0 to 25"):
        codec.encode_pin(26)


def test_commands() -> None:
    assert codec.encode_mode(2, GPIOPinMode.DIGITAL_INPUT) == b"ic"
    assert codec.encode_mode(13, GPIOPinMode.DIGITAL_INPUT_PULLUP) == b"pn"
    assert codec.encode_mode(3, GPIOPinMode.DIGITAL_OUTPUT) == b"od"
    assert codec.encode_digital_write(3, True) == b"hd"
    assert codec.encode_digital_write(3, False) == b"ld"
    assert codec.encode_digital_read(4) == b"re"
    assert codec.encode_analogue_read(14) == b"aa"
    assert codec.encode_analogue_read(19) == b"af"
    with pytest.raises(ValueError, match="analogue pins 14 to 19"):
        codec.encode_analogue_read(13)
    with pytest.raises(ValueError, match="digital modes"):
        codec.encode_mode(3, GPIOPinMode.ANALOGUE_INPUT)
    with pytest.raises(ValueError, match="one character"):
        codec.encode_command("ab", 2)


def test_initial_modes_match_j5_constructor_bytes() -> None:
    sent = b"v" + b"".join(
        codec.encode_mode(pin, GPIOPinMode.DIGITAL_INPUT) for pin in range(2, 14)
    )
    assert sent == b"vicidieifigihiiijikilimin"


def test_parse_version() -> None:
    version = codec.parse_version(b"SRduino:1")
    assert version == codec.RuggeduinoVersion("SRduino", "1")
    assert version.is_official
    custom = codec.parse_version(b"MyFirmware:extra:1\r")
    assert custom.version == "1"
    assert not custom.is_official
    with pytest.raises(UnexpectedReplyError, match="SRduino:1"):
        codec.parse_version(b"garbage")


def test_parse_digital() -> None:
    assert codec.parse_digital(b"h") is True
    assert codec.parse_digital(b"l") is False
    for bad in (b"", b"H", b"x"):
        with pytest.raises(UnexpectedReplyError, match="'h' or 'l'"):
            codec.parse_digital(bad)


def test_parse_analogue() -> None:
    assert codec.parse_analogue(b"0") == 0.0
    assert codec.parse_analogue(b"512") == 2.5
    assert codec.parse_analogue(b"1023") == 1023 / 1024 * 5
    for bad in (b"", b"abc", b"1024", b"-1"):
        with pytest.raises(UnexpectedReplyError, match="0 to 1023"):
            codec.parse_analogue(bad)


def test_the_version_is_the_generated_dataclass() -> None:
    assert_like_generated(
        codec.RuggeduinoVersion,
        [((codec.OFFICIAL_FIRMWARE_NAME, "1"), {}), ((), {"name": "custom", "version": "2.0"})],
    )
    assert codec.RuggeduinoVersion(codec.OFFICIAL_FIRMWARE_NAME, "1").is_official
    assert not codec.RuggeduinoVersion("custom", "1").is_official

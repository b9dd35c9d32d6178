from datetime import timedelta

import pytest

from j5aio.backends.hardware.sb import arduino_2019_codec as codec
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.errors import UnexpectedReplyError, UnsupportedFirmwareError


def test_request_vectors() -> None:
    assert codec.encode_pin_state(2, GPIOPinMode.DIGITAL_OUTPUT, False) == b"W 2 L\n"
    assert codec.encode_pin_state(2, GPIOPinMode.DIGITAL_OUTPUT, True) == b"W 2 H\n"
    assert codec.encode_pin_state(2, GPIOPinMode.DIGITAL_INPUT, True) == b"W 2 Z\n"
    assert codec.encode_pin_state(2, GPIOPinMode.DIGITAL_INPUT_PULLUP, False) == b"W 2 P\n"
    assert codec.encode_digital_read(2) == b"R 2\n"
    assert codec.encode_analogue_read() == b"A\n"
    assert codec.encode_ultrasound(3, 4, distance=False) == b"T 3 4\n"
    assert codec.encode_ultrasound(3, 4, distance=True) == b"U 3 4\n"
    with pytest.raises(ValueError, match="DIGITAL_INPUT"):
        codec.encode_pin_state(2, GPIOPinMode.PWM_OUTPUT, False)
    with pytest.raises(ValueError, match="one character"):
        codec.encode_command("WW")


def test_servo_vectors() -> None:
    assert codec.encode_servo(3, 0.0) == b"S 3 350\n"
    assert codec.encode_servo(4, -1.0) == b"S 4 150\n"
    assert codec.encode_servo(4, 1.0) == b"S 4 550\n"
    assert codec.encode_servo(3, None) == b"S 3 0\n"
    assert codec.servo_level(0.999) == 549  # truncated, as j5
    with pytest.raises(ValueError, match="between -1 and 1"):
        codec.servo_level(1.1)


def test_parse_reply_collects_data_and_skips_echo() -> None:
    reply = codec.parse_reply([b"# R 2", b"> H", b"+ OK"])
    assert reply == codec.Reply(("H",))
    assert codec.parse_digital(reply) is True
    assert codec.parse_digital(codec.parse_reply([b"> L", b"+ OK"])) is False


def test_parse_reply_errors() -> None:
    with pytest.raises(codec.ArduinoError, match="pin must be between 2 and 13"):
        codec.parse_reply([b"# R 1", b"- Error: pin must be between 2 and 13"])
    with pytest.raises(codec.ArduinoError, match="unknown command: Q"):
        codec.parse_reply([b"- Error, unknown command: Q"])
    with pytest.raises(UnexpectedReplyError, match="unrecognised"):
        codec.parse_reply([b"? what", b"+ OK"])
    with pytest.raises(UnexpectedReplyError, match="no final"):
        codec.parse_reply([b"> H"])


def test_parse_digital_needs_one_level() -> None:
    with pytest.raises(UnexpectedReplyError, match="one '>' line"):
        codec.parse_digital(codec.Reply(()))
    with pytest.raises(UnexpectedReplyError, match="'H' or 'L'"):
        codec.parse_digital(codec.Reply(("X",)))


def test_parse_analogue() -> None:
    reply = codec.Reply(("a0 212", "a1 0", "a2 1023", "a3 512"))
    assert codec.parse_analogue(reply, 14) == 212 / 1024 * 5
    assert codec.parse_analogue(reply, 17) == 2.5
    with pytest.raises(UnexpectedReplyError, match="no reading for a0"):
        codec.parse_analogue(codec.Reply(("a1 3",)), 14)
    with pytest.raises(UnexpectedReplyError, match="expected a number for a0"):
        codec.parse_analogue(codec.Reply(("a0 x",)), 14)


def test_parse_ultrasound() -> None:
    assert codec.parse_ultrasound_pulse(codec.Reply(("2345",))) == timedelta(microseconds=2345)
    assert codec.parse_ultrasound_pulse(codec.Reply(("0.00",))) is None
    assert codec.parse_ultrasound_distance(codec.Reply(("1230",))) == 1.23
    assert codec.parse_ultrasound_distance(codec.Reply(("0",))) is None
    with pytest.raises(UnexpectedReplyError, match="expected a number"):
        codec.parse_ultrasound_distance(codec.Reply(("far",)))


def test_is_final_line() -> None:
    assert codec.is_final_line(b"+ OK")
    assert codec.is_final_line(b"- Error: x")
    assert not codec.is_final_line(b"> H")
    assert not codec.is_final_line(b"# W 2 H")
    assert not codec.is_final_line(b"\r")
    assert codec.is_final_line(b"? garbage")
    assert codec.parse_reply([b"# A", b"", b"> a0 1", b"+ OK"]) == codec.Reply(("a0 1",))


def test_version_line() -> None:
    assert codec.parse_version_line(b"# SBDuino GPIO v2019.8.0") == "2019.8.0"
    with pytest.raises(UnexpectedReplyError, match="version line"):
        codec.parse_version_line(b"# nothing here")


@pytest.mark.parametrize("version", ["2019.6.0", "2019.6.1", "2019.7.0", "2020.1.0", "2019.8.0"])
def test_supported_versions(version: str) -> None:
    assert codec.check_version(version) == tuple(int(p) for p in version.split("."))


@pytest.mark.parametrize("version", ["2019.7", "2018.7.0", "2019.5.0", "2019.x.0", "1.2.3.4"])
def test_unsupported_versions(version: str) -> None:
    with pytest.raises(UnsupportedFirmwareError, match=r"2019\.6\.0 or later") as info:
        codec.check_version(version)
    assert info.value.found == version

import dataclasses
import struct
from datetime import timedelta

import pytest

from j5aio.backends.hardware.sr.v4 import power_fw3_codec as codec
from j5aio.errors import NotSupportedByHardwareError, UnexpectedReplyError
from tests.dataclass_twins import assert_like_generated
from tests.fresh_interpreter import printed_words


def test_read_commands() -> None:
    assert codec.ReadCommand(9, 4) == codec.FIRMWARE_VERSION
    assert codec.ReadCommand(7, 8) == codec.BATTERY
    assert codec.ReadCommand(8, 4) == codec.BUTTON
    assert codec.output_current_read(5) == codec.ReadCommand(5, 4)
    with pytest.raises(ValueError, match="outputs 0 to 5"):
        codec.output_current_read(6)


def test_led_indices() -> None:
    assert codec.led_write_index(0) == 6
    assert codec.led_write_index(1) == 7
    with pytest.raises(ValueError, match="LEDs 0"):
        codec.led_write_index(2)


def test_parse_u32() -> None:
    assert codec.parse_u32(b"\x03\x00\x00\x00") == 3
    assert codec.parse_u32(struct.pack("<I", 123456)) == 123456
    with pytest.raises(UnexpectedReplyError, match="4-byte"):
        codec.parse_u32(b"\x03\x00")


def test_parse_battery_current_first() -> None:
    reading = codec.parse_battery(struct.pack("<II", 1500, 12345))
    assert reading == codec.BatteryReading(current_ma=1500, voltage_mv=12345)
    assert reading.current == 1.5
    assert reading.voltage == 12.345
    with pytest.raises(UnexpectedReplyError, match="8-byte"):
        codec.parse_battery(b"\x00" * 4)


def test_piezo_note_rounds_half_to_even() -> None:
    assert codec.encode_piezo_note(timedelta(milliseconds=100), 440.5) == struct.pack(
        "<HH", 440, 100
    )
    assert codec.encode_piezo_note(timedelta(microseconds=2500), 1047.0) == struct.pack(
        "<HH", 1047, 2
    )


def test_piezo_limits() -> None:
    codec.encode_piezo_note(timedelta(milliseconds=65535), 65535)
    with pytest.raises(NotSupportedByHardwareError, match="65535 ms"):
        codec.encode_piezo_note(timedelta(milliseconds=65536), 440)
    with pytest.raises(NotSupportedByHardwareError, match="65535 Hz"):
        codec.encode_piezo_note(timedelta(seconds=1), 65536)
    with pytest.raises(ValueError, match="positive"):
        codec.encode_piezo_note(timedelta(seconds=-1), 440)


def test_the_index_checks_name_what_is_allowed() -> None:
    for output in range(codec.OUTPUT_COUNT):
        codec.check_output(output)
    for bad in (-1, codec.OUTPUT_COUNT):
        with pytest.raises(ValueError, match="outputs 0 to 5"):
            codec.check_output(bad)
    codec.check_led(0)
    codec.check_led(1)
    with pytest.raises(ValueError, match=r"LEDs 0 \(run\) and 1 \(error\), not 2"):
        codec.check_led(2)


def test_the_battery_reading_is_a_dataclass_of_the_codec_made_on_first_use() -> None:
    assert codec.BatteryReading.__module__ == codec.__name__
    assert "BatteryReading" in codec.__all__ and "BatteryReading" in dir(codec)
    reading = codec.parse_battery(struct.pack("<II", 2000, 11000))
    assert dataclasses.replace(reading, current_ma=1000).current == 1.0
    assert repr(reading) == "BatteryReading(current_ma=2000, voltage_mv=11000)"
    program = (
        "import sys\n"
        "from j5aio.backends.hardware.sr.v4 import power_fw3_codec as codec\n"
        "battery = 'j5aio.backends.hardware.sr.v4._power_fw3_battery'\n"
        "print(battery in sys.modules)\n"
        "print(codec.parse_battery(bytes(8)).voltage, battery in sys.modules)\n"
    )
    assert printed_words(program) == ["False", "0.0", "True"]


def test_a_read_command_is_the_generated_dataclass() -> None:
    assert_like_generated(
        codec.ReadCommand, [((7, 8), {}), ((8, 4), {}), ((), {"index": 9, "length": 4})]
    )
    assert codec.BATTERY == codec.ReadCommand(7, 8) != codec.BUTTON

from datetime import timedelta

import pytest

from j5aio.backends.hardware.sr.v4 import power_fw4_codec as codec
from j5aio.backends.hardware.sr.v4.text_protocol import (
    NackError,
    check_ack,
    command_line,
    version_matches,
)
from j5aio.components.flashing_led import LEDMode
from j5aio.errors import CommunicationError, NotSupportedByHardwareError, UnexpectedReplyError
from tests.dataclass_twins import assert_like_generated

BOARD = "SR Power Board (fw 4)"


def test_identity_is_parsed() -> None:
    identity = codec.parse_identity_reply(BOARD, b"Student Robotics:PBv4B:srABC:4.4.2")
    assert (identity.board_type, identity.asset_tag, identity.version) == (
        "PBv4B",
        "srABC",
        "4.4.2",
    )


@pytest.mark.parametrize(
    "reply",
    [
        b"Student Robotics:MCv4B:srABC:4.4",
        b"Student Robotics:PBv4B:srABC",
        b"Student Robotics:PBv4B:srABC:4.4:extra",
        b"Someone Else:PBv4B:srABC:4.4",
        b"Student Robotics:PBv4B:srABC:",
        b"\xff\xfe",
        b"",
    ],
)
def test_identity_of_another_board_is_refused(reply: bytes) -> None:
    with pytest.raises(UnexpectedReplyError, match="PBv4B") as info:
        codec.parse_identity_reply(BOARD, reply)
    assert BOARD in str(info.value)


@pytest.mark.parametrize(
    ("version", "ok"),
    [
        ("4.4", True),
        ("4.4.1", True),
        ("4.4.2", True),
        ("4.5", False),
        ("3", False),
        ("4.4.x", False),
        ("4.4.1.2", False),
        ("5.4", False),
    ],
)
def test_supported_versions(version: str, ok: bool) -> None:
    assert codec.is_supported_version(version) is ok


def test_version_matches_needs_a_numeric_patch() -> None:
    assert version_matches("4.5.0", ("4.4", "4.5"))
    assert not version_matches("4.5.", ("4.5",))
    assert not version_matches("4", ("4.4",))


@pytest.mark.parametrize(
    ("output", "enabled", "line"),
    [(0, True, b"OUT:0:SET:1\n"), (5, False, b"OUT:5:SET:0\n"), (6, True, b"OUT:6:SET:1\n")],
)
def test_output_set(output: int, enabled: bool, line: bytes) -> None:
    assert codec.encode_output_set(output, enabled) == line


def test_brain_output_is_refused_before_sending() -> None:
    with pytest.raises(NotSupportedByHardwareError, match="L2"):
        codec.encode_output_set(4, False)
    assert codec.encode_output_get(4) == b"OUT:4:GET?\n"
    assert codec.encode_output_current(4) == b"OUT:4:I?\n"


@pytest.mark.parametrize("output", [-1, 7, 100])
def test_bad_output_numbers(output: int) -> None:
    for encode in (codec.encode_output_get, codec.encode_output_current):
        with pytest.raises(ValueError, match="0 to 6"):
            encode(output)
    with pytest.raises(ValueError, match="0 to 6"):
        codec.encode_output_set(output, True)


def test_leds() -> None:
    assert codec.encode_led_set(0, LEDMode.FLASH) == b"LED:RUN:SET:F\n"
    assert codec.encode_led_set(1, LEDMode.ON) == b"LED:ERR:SET:1\n"
    assert codec.encode_led_set(1, LEDMode.OFF) == b"LED:ERR:SET:0\n"
    assert codec.encode_led_get(0) == b"LED:RUN:GET?\n"
    with pytest.raises(ValueError, match="LEDs 0"):
        codec.encode_led_get(2)
    command = codec.encode_led_get(1)
    assert codec.parse_led_mode(BOARD, command, b"F") is LEDMode.FLASH
    assert codec.parse_led_mode(BOARD, command, b"0") is LEDMode.OFF
    with pytest.raises(UnexpectedReplyError, match="LED:ERR:GET"):
        codec.parse_led_mode(BOARD, command, b"f")


@pytest.mark.parametrize(
    ("seconds", "hertz", "line"),
    [
        (0.1, 1760.0, b"NOTE:1760:100\n"),
        (1.0, 8.0, b"NOTE:8:1000\n"),
        (0.0025, 10000.4, b"NOTE:10000:2\n"),
        (0.5, 440.5, b"NOTE:440:500\n"),
    ],
)
def test_note(seconds: float, hertz: float, line: bytes) -> None:
    assert codec.encode_note(timedelta(seconds=seconds), hertz) == line


@pytest.mark.parametrize(
    ("seconds", "hertz"),
    [(1, 7.4), (1, 10000.6), (0.0004, 440), (2**31 / 1000, 440)],
)
def test_note_out_of_hardware_range(seconds: float, hertz: float) -> None:
    with pytest.raises(NotSupportedByHardwareError):
        codec.encode_note(timedelta(seconds=seconds), hertz)


def test_button() -> None:
    assert codec.parse_button(BOARD, b"1:0") == codec.ButtonLatches(True, False)
    assert codec.parse_button(BOARD, b"0:1").pressed
    assert not codec.parse_button(BOARD, b"0:0").pressed
    for reply in (b"1", b"1:0:0", b"2:0", b"true:false", b""):
        with pytest.raises(UnexpectedReplyError, match="BTN:START:GET"):
            codec.parse_button(BOARD, reply)


def test_status() -> None:
    status = codec.parse_status(BOARD, b"0,1,0,0,0,0,1:34:1:5012")
    assert status == codec.PowerStatus(
        (False, True, False, False, False, False, True),
        34,
        True,
        5012,
    )
    assert codec.parse_status(BOARD, b"0,0,0,0,0,0,0:-5:0:0").temperature == -5


@pytest.mark.parametrize(
    "reply",
    [
        b"0,0,0,0,0,0:30:0:5000",
        b"0,0,0,0,0,0,0:30:0",
        b"0,0,0,0,0,0,2:30:0:5000",
        b"0,0,0,0,0,0,0:hot:0:5000",
        b"0,0,0,0,0,0,0:30:2:5000",
        b"0,0,0,0,0,0,0:30:0:-1",
        b"0,0,0,0,0,0,0:30:0:5000:1",
    ],
)
def test_malformed_status(reply: bytes) -> None:
    with pytest.raises(UnexpectedReplyError, match=r"\*STATUS\?") as info:
        codec.parse_status(BOARD, reply)
    assert BOARD in str(info.value) and repr(reply) in str(info.value)


def test_currents_and_states() -> None:
    command = codec.encode_output_current(0)
    assert codec.parse_current_ma(BOARD, command, b"1234") == 1234
    assert codec.parse_current_ma(BOARD, codec.BATTERY_CURRENT, b"-250", signed=True) == -250
    for reply in (b"-250", b"12.5", b"+3", b" 3", b"", b"ACK"):
        with pytest.raises(UnexpectedReplyError):
            codec.parse_current_ma(BOARD, command, reply)
    state = codec.encode_output_get(1)
    assert codec.parse_output_state(BOARD, state, b"1") is True
    assert codec.parse_output_state(BOARD, state, b"0") is False
    with pytest.raises(UnexpectedReplyError):
        codec.parse_output_state(BOARD, state, b"on")


def test_nack_names_board_command_and_reason() -> None:
    command = codec.encode_output_set(0, True)
    with pytest.raises(NackError) as info:
        check_ack(BOARD, command, b"NACK:Invalid output number")
    assert isinstance(info.value, CommunicationError)
    message = str(info.value)
    assert BOARD in message and "OUT:0:SET:1" in message and "Invalid output number" in message
    with pytest.raises(NackError):
        codec.parse_status(BOARD, b"NACK:Unknown command: '*STATUS?'")
    with pytest.raises(UnexpectedReplyError, match="ACK"):
        check_ack(BOARD, command, b"OK")
    check_ack(BOARD, command, b"ACK")


def test_command_line() -> None:
    assert command_line("A", 1, "B?") == b"A:1:B?\n"


def test_the_output_check_names_what_is_allowed() -> None:
    for output in range(codec.OUTPUT_COUNT):
        codec.check_output(output)
    with pytest.raises(ValueError, match="outputs 0 to 6"):
        codec.check_output(codec.OUTPUT_COUNT)


def test_the_replies_are_the_generated_dataclasses() -> None:
    assert_like_generated(
        codec.PowerStatus,
        [
            (((False,) * 7, 25, False, 5_000), {}),
            (((True, False), -3, True, 4_990), {}),
            ((), {"overcurrent": (), "temperature": 0, "fan": True, "regulator_mv": 1}),
        ],
    )
    assert_like_generated(
        codec.ButtonLatches,
        [((True, False), {}), ((False, False), {}), ((), {"internal": False, "external": True})],
    )
    assert codec.ButtonLatches(False, True).pressed
    assert not codec.ButtonLatches(internal=False, external=False).pressed

import contextlib
import re
from datetime import timedelta

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from j5aio.backends.hardware.sb import arduino_2019_codec as codec
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.errors import CommunicationError, UnexpectedReplyError, UnsupportedFirmwareError
from tests.dataclass_twins import assert_like_generated


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
    with pytest.raises(UnexpectedReplyError, match="'x' as its reading of a0"):
        codec.parse_analogue(codec.Reply(("a0 x",)), 14)


def test_parse_ultrasound() -> None:
    assert codec.parse_ultrasound_pulse(codec.Reply(("2345",))) == timedelta(microseconds=2345)
    assert codec.parse_ultrasound_pulse(codec.Reply(("0.00",))) is None
    assert codec.parse_ultrasound_distance(codec.Reply(("1230",))) == 1.23
    assert codec.parse_ultrasound_distance(codec.Reply(("0",))) is None
    with pytest.raises(UnexpectedReplyError, match="'far' as its ultrasound distance"):
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


# -- strict parsing: hostile values and arbitrary bytes -------------------------------

HOSTILE_NUMBERS = [
    "inf",
    "nan",
    "-inf",
    "1e20",
    "9" * 400,
    "-1",
    "+5",
    " 12 ",
    "1_000",
    "0x10",
    "١٢",
    "",
    "1.5",
]


@pytest.mark.parametrize("value", [*HOSTILE_NUMBERS, "1024", "01024"])
def test_parse_analogue_refuses_what_the_firmware_cannot_send(value: str) -> None:
    with pytest.raises(UnexpectedReplyError, match=r"SourceBots Arduino sent .* a0"):
        codec.parse_analogue(codec.Reply((f"a0 {value}",)), 14)


@pytest.mark.parametrize("value", [*HOSTILE_NUMBERS[:-1], "65536", "1.0"])
def test_parse_distance_refuses_what_the_firmware_cannot_send(value: str) -> None:
    with pytest.raises(UnexpectedReplyError, match="SourceBots Arduino sent"):
        codec.parse_ultrasound_distance(codec.Reply((value,)))


@pytest.mark.parametrize("value", [*HOSTILE_NUMBERS[:-1], "4294967296", "1.234"])
def test_parse_pulse_refuses_what_the_firmware_cannot_send(value: str) -> None:
    with pytest.raises(UnexpectedReplyError, match="SourceBots Arduino sent"):
        codec.parse_ultrasound_pulse(codec.Reply((value,)))


def test_strict_parsers_accept_every_value_the_firmware_sends() -> None:
    assert codec.parse_analogue(codec.Reply(("a0 1023",)), 14) == 1023 / 1024 * 5
    assert codec.parse_ultrasound_distance(codec.Reply(("65535",))) == 65.535
    assert codec.parse_ultrasound_pulse(codec.Reply(("1234.56",))) == timedelta(
        microseconds=1234.56
    )


@pytest.mark.parametrize("version", ["2019.+6.0", "2019. 6.0", "2019.6_0.0", "2019.6.-0"])
def test_check_version_refuses_loose_numbers(version: str) -> None:
    with pytest.raises(UnsupportedFirmwareError):
        codec.check_version(version)


def test_request_ids_and_the_matching_reader() -> None:
    request = codec.with_request_id(codec.encode_digital_read(2), 7)
    assert request == b"@7 R 2\n"
    assert codec.encode_command("R", 2, request_id=7) == request
    reader = codec.reply_to(request)
    assert reader.correlates
    late = b"# @6 R 2\n@6 > H\r\n@6 + OK\r\n"
    own = b"# @7 R 2\n@7 > L\r\n@7 + OK\r\n"
    parsed = reader.parse(late + own)
    assert parsed is not None
    lines, used = parsed
    assert used == len(late + own)
    assert codec.parse_digital(codec.parse_reply(lines)) is False
    assert reader.parse(late) is None
    # An echo alone identifies the reply too (a firmware that drops the id prefix).
    assert reader.parse(b"# @7 R 2\n> H\r\n+ OK\r\n") is not None
    for bad in (0, 32768):
        with pytest.raises(ValueError, match="request id"):
            codec.with_request_id(b"R 2\n", bad)
    with pytest.raises(ValueError, match="already has"):
        codec.with_request_id(request, 8)
    with pytest.raises(ValueError, match="no request id"):
        codec.reply_to(b"R 2\n")
    with pytest.raises(ValueError, match="request id"):
        codec.encode_command("R", request_id=0)


def test_is_final_line_sees_through_request_ids() -> None:
    assert not codec.is_final_line(b"@3 > H")
    assert codec.is_final_line(b"@3 + OK")
    assert codec.parse_reply([b"# @3 R 2", b"@3 > H", b"@3 + OK"]) == codec.Reply(("H",))


@settings(max_examples=300, deadline=None)
@given(st.lists(st.binary(max_size=40), max_size=6), st.integers(14, 17))
def test_every_parser_raises_only_communication_errors_on_arbitrary_bytes(
    lines: list[bytes], pin: int
) -> None:
    try:
        reply = codec.parse_reply(lines)
    except CommunicationError:
        reply = codec.Reply(tuple(line.decode("latin-1") for line in lines))
    for parse in (
        codec.parse_digital,
        lambda r: codec.parse_analogue(r, pin),
        codec.parse_ultrasound_pulse,
        codec.parse_ultrasound_distance,
    ):
        try:
            value = parse(reply)
        except CommunicationError:
            continue
        if isinstance(value, float):
            assert 0 <= value <= 65.535
    for line in lines:
        with contextlib.suppress(CommunicationError):
            codec.check_version(codec.parse_version_line(line))
        codec.is_final_line(line)
        with contextlib.suppress(CommunicationError):
            codec.reply_to(b"@1 R 2\n").parse(line)


@settings(max_examples=300, deadline=None)
@given(st.text(max_size=30))
def test_number_parsers_on_arbitrary_text(text: str) -> None:
    for parse in (
        lambda r: codec.parse_analogue(r, 14),
        codec.parse_ultrasound_pulse,
        codec.parse_ultrasound_distance,
    ):
        data = (f"a0 {text}",) if parse is not codec.parse_ultrasound_pulse else (text,)
        with contextlib.suppress(CommunicationError):
            parse(codec.Reply(data))


@settings(max_examples=500, deadline=None)
@given(st.text(alphabet="0123456789.-+ _e\u0661\n", max_size=14) | st.text(max_size=14))
def test_number_checks_take_what_the_firmware_grammar_takes(text: str) -> None:
    """The str-method checks accept exactly the replies' number grammar (ASCII digits)."""
    assert codec._is_digits(text, 4) == bool(re.fullmatch(r"[0-9]{1,4}", text))
    assert codec._is_digits(text, 9) == bool(re.fullmatch(r"[0-9]{1,9}", text))
    assert codec._is_decimal(text, 10, 2) == bool(
        re.fullmatch(r"[0-9]{1,10}(?:\.[0-9]{1,2})?", text)
    )


def test_a_reply_is_the_generated_dataclass() -> None:
    assert_like_generated(codec.Reply, [(((),), {}), ((("1", "2"),), {}), ((), {"data": ("x",)})])


@settings(max_examples=500, deadline=None)
@given(
    st.one_of(
        st.binary(max_size=12),
        st.builds(
            lambda sign, digits, rest: b"@" + sign + digits + rest,
            st.sampled_from([b"", b"-", b"--", b"+"]),
            st.text("0123456789 x", max_size=6).map(str.encode),
            st.binary(max_size=6),
        ),
    )
)
def test_a_request_id_prefix_is_the_one_the_protocol_writes(line: bytes) -> None:
    # The protocol's request id prefix, as a regular expression: the codec checks it by hand.
    match = re.match(rb"@-?[0-9]+ ", line)
    assert codec._id_prefix_end(line) == (match.end() if match else 0)
    assert codec._strip_id(line) == (line[match.end() :] if match else line)

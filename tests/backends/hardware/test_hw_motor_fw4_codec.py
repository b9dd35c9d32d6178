import pytest

from j5aio.backends.hardware.sr.v4 import motor_fw4_codec as codec
from j5aio.backends.hardware.sr.v4.text_protocol import NackError
from j5aio.components.motor import MotorSpecialState
from j5aio.errors import UnexpectedReplyError
from tests.dataclass_twins import assert_like_generated

BOARD = "SR Motor Board (fw 4)"


def test_identity() -> None:
    identity = codec.parse_identity_reply(BOARD, b"Student Robotics:MCv4B:srXYZ:4.4.1")
    assert identity.asset_tag == "srXYZ"
    with pytest.raises(UnexpectedReplyError, match="MCv4B"):
        codec.parse_identity_reply(BOARD, b"Student Robotics:PBv4B:srXYZ:4.4.1")
    with pytest.raises(UnexpectedReplyError):
        codec.parse_identity_reply(BOARD, b"MCV4B:3")


@pytest.mark.parametrize(
    ("version", "ok"),
    [
        ("4.4", True),
        ("4.4.1", True),
        ("4.5.0", True),
        ("4.5", True),
        ("3", False),
        ("4.6", False),
        ("4.3", False),
    ],
)
def test_versions(version: str, ok: bool) -> None:
    assert codec.is_supported_version(version) is ok


@pytest.mark.parametrize(
    ("state", "line"),
    [
        (1.0, b"MOT:0:SET:1000\n"),
        (-1.0, b"MOT:0:SET:-1000\n"),
        (0.5, b"MOT:0:SET:500\n"),
        (0.0, b"MOT:0:SET:0\n"),
        (0.0005, b"MOT:0:SET:0\n"),
        (0.0015, b"MOT:0:SET:2\n"),
        (-0.123, b"MOT:0:SET:-123\n"),
        (MotorSpecialState.BRAKE, b"MOT:0:SET:0\n"),
        (MotorSpecialState.COAST, b"MOT:0:DISABLE\n"),
        (1, b"MOT:0:SET:1000\n"),
        (-1, b"MOT:0:SET:-1000\n"),
        (0, b"MOT:0:SET:0\n"),
    ],
)
def test_encode_set(state: float | MotorSpecialState, line: bytes) -> None:
    assert codec.encode_set(0, state) == line


def test_encode_refuses_bad_input() -> None:
    with pytest.raises(ValueError, match="motors 0 and 1"):
        codec.encode_set(2, 0.5)
    with pytest.raises(ValueError, match="motors 0 and 1"):
        codec.encode_get(-1)
    with pytest.raises(ValueError, match="motors 0 and 1"):
        codec.encode_current(2)
    with pytest.raises(ValueError, match="between -1 and 1"):
        codec.encode_set(0, 1.01)
    with pytest.raises(TypeError):
        codec.encode_set(0, True)
    with pytest.raises(ValueError, match="between -1 and 1"):
        codec.encode_set(0, float("nan"))
    with pytest.raises(TypeError, match="float in"):
        codec.encode_set(0, "0.5")  # type: ignore[arg-type]
    assert codec.encode_get(1) == b"MOT:1:GET?\n"
    assert codec.encode_current(1) == b"MOT:1:I?\n"


def test_reading() -> None:
    command = codec.encode_get(0)
    assert codec.parse_reading(BOARD, command, b"0:0") == codec.MotorReading(False, 0)
    assert codec.parse_reading(BOARD, command, b"1:-1000") == codec.MotorReading(True, -1000)
    for reply in (b"0:5", b"1:1001", b"1", b"2:0", b"1:x", b"1:0:0", b""):
        with pytest.raises(UnexpectedReplyError, match="MOT:0:GET") as info:
            codec.parse_reading(BOARD, command, reply)
        assert BOARD in str(info.value)
    with pytest.raises(NackError, match="Invalid motor number"):
        codec.parse_reading(BOARD, command, b"NACK:Invalid motor number")


def test_decode_reading() -> None:
    coast = codec.MotorReading(False, 0)
    stopped = codec.MotorReading(True, 0)
    assert codec.decode_reading(coast, last_set=0.5) is MotorSpecialState.COAST
    assert codec.decode_reading(stopped, last_set=None) is MotorSpecialState.BRAKE
    assert codec.decode_reading(stopped, last_set=MotorSpecialState.BRAKE) is (
        MotorSpecialState.BRAKE
    )
    assert codec.decode_reading(stopped, last_set=0.0) == 0.0
    assert codec.decode_reading(stopped, last_set=0.0004) == 0.0
    assert codec.decode_reading(codec.MotorReading(True, -250), last_set=None) == -0.25


def test_status_and_current() -> None:
    assert codec.parse_status(BOARD, b"0,1:12034") == codec.MotorStatus((False, True), 12034)
    for reply in (b"0:12000", b"0,1,0:12000", b"0,2:12000", b"0,0", b"0,0:-1", b"0,0:12.0"):
        with pytest.raises(UnexpectedReplyError, match=r"\*STATUS\?"):
            codec.parse_status(BOARD, reply)
    command = codec.encode_current(1)
    assert codec.parse_current_ma(BOARD, command, b"5000") == 5000
    with pytest.raises(UnexpectedReplyError):
        codec.parse_current_ma(BOARD, command, b"-1")


def test_identify_probe_starts_with_the_fw3_resync_byte() -> None:
    assert codec.IDENTIFY_PROBE == b"\x00\n*IDN?\n"
    # no byte after the resync is a firmware 3 command (0x01 to 0x04)
    assert not set(codec.IDENTIFY_PROBE[1:]) & {1, 2, 3, 4}


def test_the_motor_check_names_what_is_allowed() -> None:
    codec.check_motor(0)
    codec.check_motor(1)
    with pytest.raises(ValueError, match="motors 0 and 1, not 2"):
        codec.check_motor(2)


def test_the_replies_are_the_generated_dataclasses() -> None:
    assert_like_generated(
        codec.MotorReading,
        [((True, 500), {}), ((False, 0), {}), ((), {"enabled": True, "value": -1})],
    )
    assert_like_generated(
        codec.MotorStatus,
        [(((False, True), 11_900), {}), (((), 0), {}), ((), {"faults": (True,), "input_mv": 12})],
    )
    assert (
        codec.MotorReading(True, 5) == codec.MotorReading(True, 5) != codec.MotorReading(False, 5)
    )

import pytest

from j5aio.backends.hardware.sr.v4 import motor_fw3_codec as codec
from j5aio.components.motor import MotorSpecialState
from j5aio.errors import UnexpectedReplyError


@pytest.mark.parametrize(
    ("state", "byte"),
    [
        (1.0, 0xE4),  # 100 steps: full duty, no further
        (0.65, 0xC1),
        (-1.0, 0x1C),
        (0.0, 0x80),
        (0.5, 178),
        (0.005, 128),  # 0.5 rounds half to even: 0
        (-0.5, 78),
        (MotorSpecialState.BRAKE, 0x02),
        (MotorSpecialState.COAST, 0x01),
    ],
)
def test_encode_speed_is_linear_in_duty(state: float | MotorSpecialState, byte: int) -> None:
    assert codec.encode_speed(state) == byte


@pytest.mark.parametrize(
    ("state", "byte"),
    [
        (1.0, 0xFD),
        (0.65, 0xD1),
        (-1.0, 0x03),
        (0.0, 0x80),
        (0.5, 190),  # 62.5 rounds half to even: 62
        (-0.5, 66),  # -62.5 -> -62
        (MotorSpecialState.BRAKE, 0x02),
    ],
)
def test_j5_scale_matches_j5s_bytes(state: float | MotorSpecialState, byte: int) -> None:
    assert codec.encode_speed(state, scale=codec.J5_SCALE) == byte


def test_linear_speed_bytes_stay_clear_of_the_magic_bytes() -> None:
    bytes_sent = {codec.encode_speed(p / 1000) for p in range(-1000, 1001)}
    assert min(bytes_sent) == 28 and max(bytes_sent) == 228


def test_unknown_scale_is_refused() -> None:
    with pytest.raises(ValueError, match="LINEAR_SCALE"):
        codec.encode_speed(0.5, scale=50)
    with pytest.raises(ValueError, match="J5_SCALE"):
        codec.decode_speed(200, scale=50)


@pytest.mark.parametrize("power", [1.01, -1.5, float("nan")])
def test_encode_speed_refuses_out_of_range(power: float) -> None:
    with pytest.raises(ValueError, match="between -1 and 1"):
        codec.encode_speed(power)


@pytest.mark.parametrize("power", ["1", None, True])
def test_encode_speed_refuses_wrong_type(power: object) -> None:
    with pytest.raises(TypeError, match="MotorSpecialState"):
        codec.encode_speed(power)  # type: ignore[arg-type]


def test_motor_commands() -> None:
    assert codec.encode_motor_command(0, MotorSpecialState.BRAKE) == b"\x02\x02"
    assert codec.encode_motor_command(1, MotorSpecialState.BRAKE) == b"\x03\x02"
    assert codec.encode_motor_command(1, 1.0) == b"\x03\xe4"
    assert codec.encode_motor_command(1, 1.0, scale=codec.J5_SCALE) == b"\x03\xfd"
    with pytest.raises(ValueError, match="motors 0 and 1"):
        codec.encode_motor_command(2, 0.0)


def test_decode_speed_inverts_encode() -> None:
    assert codec.decode_speed(0) is None
    assert codec.decode_speed(1) is MotorSpecialState.COAST
    assert codec.decode_speed(2) is MotorSpecialState.BRAKE
    assert codec.decode_speed(0xE4) == 1.0
    assert codec.decode_speed(0xFD, scale=codec.J5_SCALE) == 1.0
    assert codec.decode_speed(0x80) == 0.0
    with pytest.raises(ValueError, match=r"0\.\.255"):
        codec.decode_speed(256)


def test_version_reply_round_trip() -> None:
    assert codec.RESYNC_AND_VERSION_QUERY == b"\x00\x01"
    assert codec.encode_version_reply() == b"MCV4B:3\n"
    assert codec.parse_version_reply(b"MCV4B:3") == "3"
    assert codec.parse_version_reply(b"MCV4B:4\r\n") == "4"


@pytest.mark.parametrize(
    "line",
    [
        b"MCV4A:3",
        b"MCV4B",
        b"",
        b"hello",
        b"MCV4B:",
        b"MCV4B:123456",
        b"MCV4B:-1",
        b"MCV4B: 3",
        b"MCV4B:3.0",
        "MCV4B:\u0663".encode(),
    ],
)
def test_parse_version_reply_refuses_other_models(line: bytes) -> None:
    with pytest.raises(UnexpectedReplyError, match="motor board"):
        codec.parse_version_reply(line)

import pytest

from j5aio.backends.hardware.sr.v4 import servo_fw2_codec as codec


@pytest.mark.parametrize(
    ("position", "w_value"),
    [(0.0, 0), (1.0, 100), (-1.0, 0xFF9C), (0.5, 50), (0.005, 0), (0.015, 2), (-0.005, 0)],
)
def test_encode_position(position: float, w_value: int) -> None:
    assert codec.encode_position(position) == w_value


def test_decode_position() -> None:
    assert codec.decode_position(0xFF9C) == -100
    assert codec.decode_position(100) == 100


def test_encode_position_refuses_out_of_range() -> None:
    with pytest.raises(ValueError, match="between -1 and 1"):
        codec.encode_position(1.5)


def test_servo_index() -> None:
    assert codec.servo_write_index(11) == 11
    for bad in (12, -1, True, 1.0):
        with pytest.raises(ValueError, match="servos 0 to 11"):
            codec.servo_write_index(bad)  # type: ignore[arg-type]
    assert codec.FIRMWARE_VERSION.index == 9
    assert codec.INIT_WRITE == 12

from __future__ import annotations

import pytest
from hypothesis import given

from j5aio.simulator import (
    MotorMode,
    MotorOutput,
    SimulatorUnpluggedError,
    SRMotorBoardFw3Simulator,
)
from tests.dataclass_twins import assert_like_generated

from .split_helpers import cut_lists, feed, pieces, streams

COAST = MotorOutput(MotorMode.COAST)
BRAKE = MotorOutput(MotorMode.BRAKE)


@pytest.fixture
def board() -> SRMotorBoardFw3Simulator:
    return SRMotorBoardFw3Simulator("srMOTOR")


def test_port_description(board: SRMotorBoardFw3Simulator) -> None:
    assert board.baudrate == 1_000_000
    assert board.boot_delay == 0
    assert (board.usb_vid, board.usb_pid) == (0x0403, 0x6001)
    assert (board.manufacturer, board.product) == ("Student Robotics", "MCV4B")
    assert board.serial_number == "srMOTOR"
    assert board.version == 3


def test_power_up_state(board: SRMotorBoardFw3Simulator) -> None:
    assert board.motors == (COAST, COAST)
    assert board.awaiting_speed is None
    assert not board.in_bootloader


def test_version(board: SRMotorBoardFw3Simulator) -> None:
    assert board.receive(b"\x01") == b"MCV4B:3\n"
    assert board.receive(b"\x01\x01") == b"MCV4B:3\nMCV4B:3\n"


def test_j5_handshake(board: SRMotorBoardFw3Simulator) -> None:
    assert board.open() == b""
    assert board.receive(b"\x01") == b"MCV4B:3\n"
    assert board.receive(b"\x02\x02\x03\x02") == b""
    assert board.motors == (BRAKE, BRAKE)


def test_open_does_not_reset(board: SRMotorBoardFw3Simulator) -> None:
    board.receive(b"\x02\xfd\x03")
    assert board.open() == b""
    assert board.motors[0].mode is MotorMode.FORWARD
    assert board.awaiting_speed == 1


@pytest.mark.parametrize(
    ("byte", "mode", "steps", "duty"),
    [
        (0xFD, MotorMode.FORWARD, 125, 1.0),  # j5 power 1.0
        (0xD1, MotorMode.FORWARD, 81, 0.81),  # j5 power 0.65
        (0x80, MotorMode.FORWARD, 0, 0.0),  # j5 power 0
        (0xFF, MotorMode.FORWARD, 127, 1.0),
        (0xE4, MotorMode.FORWARD, 100, 1.0),  # saturation starts at |s| = 100
        (0xE3, MotorMode.FORWARD, 99, 0.99),
        (0x7F, MotorMode.REVERSE, 1, 0.01),
        (0x1C, MotorMode.REVERSE, 100, 1.0),
        (0x1D, MotorMode.REVERSE, 99, 0.99),
        (0x03, MotorMode.REVERSE, 125, 1.0),  # j5 power -1.0
    ],
)
def test_speed_bytes(
    board: SRMotorBoardFw3Simulator, byte: int, mode: MotorMode, steps: int, duty: float
) -> None:
    assert board.receive(bytes([0x02, byte])) == b""
    motor = board.motors[0]
    assert motor == MotorOutput(mode, steps)
    assert motor.duty == pytest.approx(duty)
    assert motor.duty_percent == round(duty * 100)
    expected_power = -duty if mode is MotorMode.REVERSE else duty
    assert motor.power == pytest.approx(expected_power)
    assert board.motors[1] == COAST


def test_forward_saturated(board: SRMotorBoardFw3Simulator) -> None:
    board.receive(b"\x02\xfd")
    assert board.motors[0].mode is MotorMode.FORWARD
    assert board.motors[0].duty_percent == 100


def test_coast_and_brake(board: SRMotorBoardFw3Simulator) -> None:
    board.receive(b"\x03\xfd\x03\x02")
    assert board.motors[1] == BRAKE
    board.receive(b"\x03\x01")
    assert board.motors[1] == COAST
    assert BRAKE.duty == COAST.duty == 0.0
    assert BRAKE.power == COAST.power == 0.0


def test_speed_byte_zero_is_ignored(board: SRMotorBoardFw3Simulator) -> None:
    board.receive(b"\x02\xa0")
    before = board.motors
    assert board.receive(b"\x02\x00") == b""
    assert board.motors == before
    assert board.awaiting_speed is None
    assert board.receive(b"\x01") == b"MCV4B:3\n"


def test_zero_is_a_no_op_when_idle(board: SRMotorBoardFw3Simulator) -> None:
    assert board.receive(b"\x00\x00\x00") == b""
    assert board.motors == (COAST, COAST)


def test_leading_zero_resynchronises_a_half_sent_command(board: SRMotorBoardFw3Simulator) -> None:
    board.receive(b"\x03\xa0")
    board.receive(b"\x02")  # the host dies here
    assert board.awaiting_speed == 0
    assert board.receive(b"\x00\x01") == b"MCV4B:3\n"
    assert board.motors[0] == COAST
    assert board.motors[1].mode is MotorMode.FORWARD


def test_without_resync_a_version_byte_becomes_coast(board: SRMotorBoardFw3Simulator) -> None:
    board.receive(b"\x02\xa0\x02")
    assert board.receive(b"\x01") == b""
    assert board.motors[0] == COAST


@pytest.mark.parametrize("byte", [0x05, 0x10, 0x56, 0x80, 0xFF])
def test_other_command_bytes_are_ignored(board: SRMotorBoardFw3Simulator, byte: int) -> None:
    assert board.receive(bytes([byte])) == b""
    assert board.awaiting_speed is None
    assert board.motors == (COAST, COAST)


def test_bootloader_then_silence(board: SRMotorBoardFw3Simulator) -> None:
    board.receive(b"\x02\xfd")
    assert board.receive(b"\x04\x01\x02\xfd") == b"Entering bootloader\n"
    assert board.in_bootloader
    assert board.motors == (COAST, COAST)
    assert board.receive(b"\x01") == b""
    assert board.open() == b""
    assert board.receive(b"\x01") == b""
    assert board.reset() == b""
    assert not board.in_bootloader
    assert board.receive(b"\x01") == b"MCV4B:3\n"


def test_reset_coasts_and_clears_the_parser(board: SRMotorBoardFw3Simulator) -> None:
    board.receive(b"\x02\xfd\x03")
    board.reset()
    assert board.motors == (COAST, COAST)
    assert board.awaiting_speed is None


def test_unplugging_the_ftdi_cable_keeps_the_board_running(
    board: SRMotorBoardFw3Simulator,
) -> None:
    board.receive(b"\x02\xfd\x03")
    board.unplug()
    assert not board.connected
    with pytest.raises(SimulatorUnpluggedError):
        board.receive(b"\x01")
    board.plug()
    assert board.connected
    assert board.motors[0].mode is MotorMode.FORWARD
    assert board.awaiting_speed == 1


FRAGMENTS = [b"\x00", b"\x01", b"\x02", b"\x03", b"\x02\xfd", b"\x03\x01", b"\x02\x02", b"\x04"]


@given(streams(FRAGMENTS), cut_lists)
def test_split_input_gives_the_same_result(data: bytes, cuts: list[int]) -> None:
    whole = SRMotorBoardFw3Simulator("a")
    split = SRMotorBoardFw3Simulator("b")
    assert feed(split, pieces(data, cuts)) == whole.receive(data)
    assert split.motors == whole.motors
    assert split.awaiting_speed == whole.awaiting_speed
    assert split.in_bootloader == whole.in_bootloader


@given(streams(FRAGMENTS))
def test_one_byte_at_a_time_gives_the_same_result(data: bytes) -> None:
    whole = SRMotorBoardFw3Simulator("a")
    split = SRMotorBoardFw3Simulator("b")
    assert feed(split, [bytes([byte]) for byte in data]) == whole.receive(data)
    assert split.motors == whole.motors


def test_motor_output_is_the_generated_dataclass() -> None:
    assert_like_generated(
        MotorOutput,
        [((MotorMode.COAST,), {}), ((MotorMode.FORWARD, 50), {}), ((MotorMode.FORWARD,), {})],
    )

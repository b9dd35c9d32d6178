from __future__ import annotations

import errno

import pytest
import usb.core

from j5aio.simulator import SRServoBoardFw2Simulator

from .usb_helpers import READ, REQUEST, WRITE, read, read_u32, write

VERSION = 9
INITIALISE = 12


@pytest.fixture
def board() -> SRServoBoardFw2Simulator:
    return SRServoBoardFw2Simulator("srSERVO")


def assert_raises_errno(board: SRServoBoardFw2Simulator, number: int, *args: object) -> None:
    with pytest.raises(usb.core.USBError) as raised:
        board.ctrl_transfer(*args)  # type: ignore[arg-type]
    assert raised.value.errno == number


def test_usb_identity(board: SRServoBoardFw2Simulator) -> None:
    assert (board.idVendor, board.idProduct, board.bcdDevice) == (0x1BDA, 0x0011, 0x0402)
    assert board.manufacturer == "Student Robotics"
    assert board.product == "Servo Board v4"
    assert board.serial_number == "srSERVO"
    assert len(board.get_active_configuration().interfaces()) == 1


def test_version_is_2(board: SRServoBoardFw2Simulator) -> None:
    assert read(board, VERSION, 4) == b"\x02\x00\x00\x00"
    assert read(board, VERSION, 16) == b"\x02\x00\x00\x00"
    assert board.version == 2


@pytest.mark.parametrize("index", [0, 8, 10, 11, 12, 0xFFFF])
def test_any_other_read_stalls(board: SRServoBoardFw2Simulator, index: int) -> None:
    assert_raises_errno(board, errno.EPIPE, READ, REQUEST, 0, index, 4)


def test_short_version_read_stalls(board: SRServoBoardFw2Simulator) -> None:
    assert_raises_errno(board, errno.EPIPE, READ, REQUEST, 0, VERSION, 3)


def test_wrong_request_stalls(board: SRServoBoardFw2Simulator) -> None:
    assert_raises_errno(board, errno.EPIPE, 0xC0, REQUEST, 0, VERSION, 4)
    assert_raises_errno(board, errno.EPIPE, WRITE, 1, 0, 0, None)


@pytest.mark.parametrize("index", [13, 14, 64, 0xFFFF])
def test_write_beyond_12_stalls(board: SRServoBoardFw2Simulator, index: int) -> None:
    assert_raises_errno(board, errno.EPIPE, WRITE, REQUEST, 0, index, None)


@pytest.mark.parametrize(
    ("value", "position"),
    [
        (0, 0),
        (50, 50),
        (100, 100),
        (0xFF9C, -100),
        (-100, -100),  # pyusb passes a negative int through ctypes, which wraps it
        (-37, -37),
        (150, 100),
        (0x7FFF, 100),
        (0x8000, -100),
        (0xFF00, -100),
    ],
)
def test_positions_are_signed_16_bit_and_clamped(
    board: SRServoBoardFw2Simulator, value: int, position: int
) -> None:
    assert write(board, 4, value) == 0
    assert board.positions[4] == position


def test_no_pulses_before_initialise(board: SRServoBoardFw2Simulator) -> None:
    write(board, 0, 20)
    assert not board.initialised
    assert board.pulse_widths_us == (None,) * 12
    write(board, INITIALISE)
    assert board.initialised
    assert board.init_requests == 1
    assert board.pulse_widths_us[0] == 1600
    assert board.pulse_widths_us[1] == 1500


def test_pulse_width_is_1500_plus_5_per_step(board: SRServoBoardFw2Simulator) -> None:
    write(board, INITIALISE)
    write(board, 0, -100)
    write(board, 11, 100)
    write(board, 5, -1)
    widths = board.pulse_widths_us
    assert (widths[0], widths[11], widths[5]) == (1000, 2000, 1495)


def test_j5_construction_traffic(board: SRServoBoardFw2Simulator) -> None:
    assert read_u32(board, VERSION) == 2
    write(board, INITIALISE)
    for servo in range(12):
        write(board, servo, 0)
    assert board.positions == (0,) * 12
    assert board.pulse_widths_us == (1500,) * 12
    assert board.init_requests == 1


def test_without_12v_initialise_times_out_and_the_board_hangs() -> None:
    board = SRServoBoardFw2Simulator("s", has_12v=False)
    assert not board.has_12v
    assert read_u32(board, VERSION) == 2  # nothing touches the expander yet
    with pytest.raises(usb.core.USBTimeoutError) as raised:
        write(board, INITIALISE)
    assert raised.value.errno == errno.ETIMEDOUT == 110
    assert raised.value.backend_error_code == -7
    assert board.hung
    assert not board.initialised
    assert_raises_errno(board, errno.ETIMEDOUT, READ, REQUEST, 0, VERSION, 4)
    assert_raises_errno(board, errno.ETIMEDOUT, WRITE, REQUEST, 10, 0, None)
    board.has_12v = True  # the set-up completes
    assert not board.hung
    assert board.initialised
    assert read_u32(board, VERSION) == 2


def test_restoring_12v_without_a_hang_changes_nothing() -> None:
    board = SRServoBoardFw2Simulator("s", has_12v=False)
    board.has_12v = True
    assert not board.initialised


def test_power_cycle(board: SRServoBoardFw2Simulator) -> None:
    write(board, INITIALISE)
    write(board, 3, 30)
    board.power_cycle()
    assert board.positions == (0,) * 12
    assert not board.initialised
    assert board.init_requests == 0


def test_unplugged_transfers_raise_enodev(board: SRServoBoardFw2Simulator) -> None:
    write(board, INITIALISE)
    write(board, 2, 10)
    board.unplug()
    assert_raises_errno(board, errno.ENODEV, READ, REQUEST, 0, VERSION, 4)
    assert_raises_errno(board, errno.ENODEV, WRITE, REQUEST, 0, 1, None)
    board.plug()
    assert board.positions[2] == 10  # servos keep pulsing: state survives
    assert board.initialised

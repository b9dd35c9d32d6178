from __future__ import annotations

import pytest
from hypothesis import given

from j5aio.simulator import (
    PinMode,
    SimulatorUnpluggedError,
    SRRuggeduinoSimulator,
    UsbIdentity,
)

from .split_helpers import cut_lists, feed, pieces, streams


@pytest.fixture
def board() -> SRRuggeduinoSimulator:
    return SRRuggeduinoSimulator("75230313833351619081")


@pytest.fixture
def board2() -> SRRuggeduinoSimulator:
    return SRRuggeduinoSimulator("R2", firmware_version=2)


def pin(number: int) -> bytes:
    return bytes([ord("a") + number])


def test_port_description(board: SRRuggeduinoSimulator) -> None:
    assert board.baudrate == 115_200
    assert board.boot_delay == 1.5
    assert (board.usb_vid, board.usb_pid) == (0x2341, 0x0043)
    assert board.manufacturer == "Arduino (www.arduino.cc)"
    assert board.product is None
    assert board.serial_number == "75230313833351619081"
    assert board.firmware_version == 1


def test_custom_usb_identity() -> None:
    identity = UsbIdentity(0x10C4, 0xEA60, "Silicon Labs", "CP2102")
    board = SRRuggeduinoSimulator("x", usb_identity=identity)
    assert (board.usb_vid, board.usb_pid, board.manufacturer, board.product) == identity


def test_only_versions_1_and_2_exist() -> None:
    with pytest.raises(ValueError, match="1 and 2"):
        SRRuggeduinoSimulator("x", firmware_version=3)


def test_open_prints_nothing(board: SRRuggeduinoSimulator) -> None:
    assert board.open() == b""


def test_version(board: SRRuggeduinoSimulator, board2: SRRuggeduinoSimulator) -> None:
    assert board.receive(b"v") == b"SRduino:1\n"
    assert board2.receive(b"v") == b"SRduino:2\n"


def test_j5_constructor_sequence(board: SRRuggeduinoSimulator) -> None:
    assert board.receive(b"vicidieifigihiiijikilimin") == b"SRduino:1\n" + b"\n" * 12
    assert all(board.pin_mode(number) is PinMode.INPUT for number in range(2, 14))


def test_every_command_ends_with_a_newline(board: SRRuggeduinoSimulator) -> None:
    assert board.receive(b"ic") == b"\n"
    assert board.receive(b"pc") == b"\n"
    assert board.receive(b"oc") == b"\n"
    assert board.receive(b"hc") == b"\n"
    assert board.receive(b"lc") == b"\n"
    assert board.receive(b"rc") == b"l\n"
    assert board.receive(b"ao") == b"0\n"


@pytest.mark.parametrize("byte", [b"x", b"\n", b"\x00", b"V", b"z", b"u"])
def test_anything_else_is_ignored_with_a_newline(board: SRRuggeduinoSimulator, byte: bytes) -> None:
    assert board.receive(byte) == b"\n"
    assert board.awaiting_pin is None


def test_output_high_and_low(board: SRRuggeduinoSimulator) -> None:
    board.receive(b"o" + pin(13) + b"h" + pin(13))
    assert board.pin_mode(13) is PinMode.OUTPUT
    assert board.output_level(13) is True
    assert board.receive(b"r" + pin(13)) == b"h\n"
    board.receive(b"l" + pin(13))
    assert board.receive(b"r" + pin(13)) == b"l\n"


def test_j5_0_12_write_without_o_only_toggles_the_pull_up(board: SRRuggeduinoSimulator) -> None:
    board.receive(b"hd")
    assert board.pin_mode(3) is PinMode.INPUT_PULLUP
    assert board.receive(b"rd") == b"h\n"
    board.receive(b"ld")
    assert board.pin_mode(3) is PinMode.INPUT
    assert board.receive(b"rd") == b"l\n"


def test_pull_up_and_outside_levels(board: SRRuggeduinoSimulator) -> None:
    board.receive(b"pe")
    assert board.pin_mode(4) is PinMode.INPUT_PULLUP
    assert board.receive(b"re") == b"h\n"
    board.set_input_level(4, False)  # a switch to ground
    assert board.receive(b"re") == b"l\n"
    board.receive(b"ie")
    board.set_input_level(4, True)
    assert board.receive(b"re") == b"h\n"
    assert board.pin_level(4) is True


def test_analogue_by_pin_and_by_channel(board: SRRuggeduinoSimulator) -> None:
    board.set_analogue(14, volts=2.5)
    board.set_analogue(19, raw=1023)
    assert board.receive(b"ao") == b"512\n"  # pin 14 (sr-robot3)
    assert board.receive(b"aa") == b"512\n"  # channel 0 (j5)
    assert board.receive(b"at") == b"1023\n"
    assert board.receive(b"af") == b"1023\n"


def test_analogue_pin_byte_quirks(board: SRRuggeduinoSimulator) -> None:
    board.set_analogue(16, raw=333)  # A2
    assert board.receive(b"ac") == b"333\n"  # pin 2 is taken as channel 2
    assert board.receive(b"aA") == b"333\n"  # 'A' - 'a' = -32 = 224 -> 210 & 7 = 2
    assert board.receive(b"au") == b"0\n"  # pin 20 -> channel 6, not bonded out


def test_unknown_pins_are_ignored(board: SRRuggeduinoSimulator) -> None:
    assert board.receive(b"oz") == b"\n"
    assert board.receive(b"hz") == b"\n"
    assert board.receive(b"rz") == b"l\n"
    assert board.receive(b"r\n") == b"l\n"  # the newline byte is taken as the pin


def test_waits_for_the_pin_byte(board: SRRuggeduinoSimulator) -> None:
    assert board.receive(b"r") == b""
    assert board.awaiting_pin == "r"
    assert board.receive(b"v") == b"l\n"  # 'v' is the pin (21), not a command
    assert board.awaiting_pin is None


def test_ultrasound_is_not_in_version_1(board: SRRuggeduinoSimulator) -> None:
    board.set_ultrasound_distance(2, 3, 1.0)
    assert board.receive(b"ucd") == b"\n\n\n"
    assert board.pin_mode(2) is PinMode.INPUT


def test_ultrasound_in_version_2(board2: SRRuggeduinoSimulator) -> None:
    board2.set_ultrasound_distance(2, 3, 1.23)
    assert board2.ultrasound_echo(2, 3) == 7134
    assert board2.receive(b"u") == b""
    assert board2.awaiting_pin == "u"
    assert board2.receive(b"c") == b""
    assert board2.receive(b"d") == b"1230\n"
    assert board2.pin_mode(2) is PinMode.OUTPUT
    assert board2.output_level(2) is False
    assert board2.pin_mode(3) is PinMode.INPUT


def test_ultrasound_formula_and_timeout(board2: SRRuggeduinoSimulator) -> None:
    board2.set_ultrasound_echo(5, 6, 5800)
    assert board2.receive(b"ufg") == b"1000\n"  # 5 * 5800 // 29
    board2.set_ultrasound_echo(5, 6, 60_000)
    assert board2.receive(b"ufg") == b"10344\n"
    board2.set_ultrasound_echo(5, 6, 60_001)  # longer than the 60 ms pulseIn timeout
    assert board2.receive(b"ufg") == b"0\n"
    board2.set_ultrasound_echo(5, 6, None)
    assert board2.receive(b"ufg") == b"0\n"
    board2.set_ultrasound_distance(5, 6, 20.0)  # beyond range
    assert board2.receive(b"ufg") == b"0\n"
    board2.set_ultrasound_distance(5, 6, None)
    assert board2.ultrasound_echo(5, 6) is None


def test_ultrasound_needs_the_right_pin_pair(board2: SRRuggeduinoSimulator) -> None:
    board2.set_ultrasound_distance(2, 3, 1.0)
    assert board2.receive(b"udc") == b"0\n"
    assert board2.receive(b"ucz") == b"0\n"


def test_ultrasound_on_one_pin_ends_as_an_input(board2: SRRuggeduinoSimulator) -> None:
    board2.set_ultrasound_distance(7, 7, 0.5)
    board2.receive(b"ph")
    assert board2.receive(b"uhh") == b"500\n"
    assert board2.pin_mode(7) is PinMode.INPUT


def test_ultrasound_settings_are_checked(board2: SRRuggeduinoSimulator) -> None:
    with pytest.raises(IndexError):
        board2.set_ultrasound_distance(2, 20, 1.0)
    with pytest.raises(ValueError):
        board2.set_ultrasound_distance(2, 3, -1.0)
    with pytest.raises(ValueError):
        board2.set_ultrasound_echo(2, 3, -1)


def test_a_distance_of_zero(board2: SRRuggeduinoSimulator) -> None:
    board2.set_ultrasound_distance(2, 3, 0.0)
    assert board2.receive(b"ucd") == b"0\n"


def test_open_reboots(board: SRRuggeduinoSimulator) -> None:
    board.receive(b"ocho" + b"r")
    board.set_analogue(14, raw=5)
    board.set_input_level(9, True)
    assert board.open() == b""
    assert board.pin_mode(2) is PinMode.INPUT
    assert board.awaiting_pin is None
    assert board.receive(b"aa") == b"5\n"  # the outside world is unchanged
    assert board.receive(b"rj") == b"h\n"


def test_unplug_and_plug_reboots(board: SRRuggeduinoSimulator) -> None:
    board.receive(b"oc")
    board.unplug()
    with pytest.raises(SimulatorUnpluggedError):
        board.receive(b"v")
    board.plug()
    assert board.pin_mode(2) is PinMode.INPUT
    assert board.receive(b"v") == b"SRduino:1\n"


FRAGMENTS = [b"v", b"o", b"i", b"p", b"h", b"l", b"r", b"a", b"u", b"c", b"n", b"o", b"ucd"]


def snapshot(board: SRRuggeduinoSimulator) -> tuple[object, ...]:
    return (
        tuple(board.pin_mode(number) for number in range(20)),
        tuple(board.output_level(number) for number in range(20)),
        board.awaiting_pin,
    )


@given(streams(FRAGMENTS), cut_lists)
def test_split_input_gives_the_same_result(data: bytes, cuts: list[int]) -> None:
    whole = SRRuggeduinoSimulator("a", firmware_version=2)
    split = SRRuggeduinoSimulator("b", firmware_version=2)
    for board in (whole, split):
        board.set_ultrasound_distance(2, 3, 0.4)
        board.set_analogue(14, raw=77)
    assert feed(split, pieces(data, cuts)) == whole.receive(data)
    assert snapshot(split) == snapshot(whole)


@given(streams(FRAGMENTS))
def test_one_byte_at_a_time_gives_the_same_result(data: bytes) -> None:
    whole = SRRuggeduinoSimulator("a")
    split = SRRuggeduinoSimulator("b")
    assert feed(split, [bytes([byte]) for byte in data]) == whole.receive(data)
    assert snapshot(split) == snapshot(whole)

from __future__ import annotations

import pytest
from hypothesis import given

from j5aio.simulator import (
    PinMode,
    SBArduinoFirmware,
    SBArduinoSimulator,
    SimulatorUnpluggedError,
)

from .split_helpers import cut_lists, feed, pieces, streams


@pytest.fixture
def board() -> SBArduinoSimulator:
    board = SBArduinoSimulator("SB0")
    board.open()
    return board


@pytest.fixture
def board8() -> SBArduinoSimulator:
    board = SBArduinoSimulator("SB8", firmware_version="2019.8.0")
    board.open()
    return board


def ok(echo: bytes, *data: bytes) -> bytes:
    return b"# " + echo + b"\n" + b"".join(b"> " + item + b"\r\n" for item in data) + b"+ OK\r\n"


def error(echo: bytes, message: bytes) -> bytes:
    return b"# " + echo + b"\n- Error: " + message + b"\r\n"


# --- port, boot, version ---


def test_port_description(board: SBArduinoSimulator) -> None:
    assert board.baudrate == 115_200
    assert board.boot_delay == 1.5
    assert (board.usb_vid, board.usb_pid) == (0x2341, 0x0043)
    assert board.serial_number == "SB0"
    assert board.firmware_version is SBArduinoFirmware.V2019_6_0


def test_boot_banner() -> None:
    board = SBArduinoSimulator("x")
    assert board.open() == b"# Booted\n# SBDuino GPIO v2019.6.0\r\n"
    board8 = SBArduinoSimulator("x", firmware_version=SBArduinoFirmware.V2019_8_0)
    assert board8.open() == b"# Booted\n# SBDuino GPIO v2019.8.0\r\n"
    assert board8.reset() == b"# Booted\n# SBDuino GPIO v2019.8.0\r\n"


def test_unknown_firmware_version() -> None:
    with pytest.raises(ValueError):
        SBArduinoSimulator("x", firmware_version="2019.7.0")


def test_version_command(board: SBArduinoSimulator, board8: SBArduinoSimulator) -> None:
    assert board.receive(b"V\n") == ok(b"V", b"SBDuino GPIO v2019.6.0")
    assert board8.receive(b"V\n") == ok(b"V", b"SBDuino GPIO v2019.8.0")
    assert board.version_string == "SBDuino GPIO v2019.6.0"
    assert board.receive(b"V extra\n") == ok(b"V extra", b"SBDuino GPIO v2019.6.0")


def test_boot_sets_pins_2_to_13_to_input(board: SBArduinoSimulator) -> None:
    board.receive(b"W 13 H\nW 2 P\n")
    board.reset()
    assert all(board.pin_mode(pin) is PinMode.INPUT for pin in range(2, 14))


def test_j5_construction_traffic(board: SBArduinoSimulator) -> None:
    for pin in range(2, 14):
        command = b"W %d Z" % pin
        assert board.receive(command + b"\n") == ok(command)
        assert board.pin_mode(pin) is PinMode.INPUT


# --- W and R ---


def test_write_high(board: SBArduinoSimulator) -> None:
    assert board.receive(b"W 2 H\n") == b"# W 2 H\n+ OK\r\n"
    assert board.pin_mode(2) is PinMode.OUTPUT
    assert board.output_level(2) is True


@pytest.mark.parametrize(
    ("command", "mode", "level"),
    [
        (b"W 2 L", PinMode.OUTPUT, False),
        (b"W 2 P", PinMode.INPUT_PULLUP, True),
        (b"W 2 Z", PinMode.INPUT, False),
        (b"W2 H", PinMode.OUTPUT, True),
        (b"W 2 HIGH", PinMode.OUTPUT, True),
        (b"W 65538 H", PinMode.OUTPUT, True),  # the pin is a 16-bit int: 65538 is 2
    ],
)
def test_write_modes(board: SBArduinoSimulator, command: bytes, mode: PinMode, level: bool) -> None:
    assert board.receive(command + b"\n") == ok(command)
    assert board.pin_mode(2) is mode
    assert board.pin_level(2) is level


@pytest.mark.parametrize(
    ("command", "message"),
    [
        (b"W", b"Arguments Needed: <num> <state>"),
        (b"W 2", b"Arguments Needed: <num> <state>"),
        (b"W 2 H X", b"Arguments Needed: <num> <state>"),
        (b"W 1 H", b"pin must be between 2 and 13"),
        (b"W 14 H", b"pin must be between 2 and 13"),
        (b"W x H", b"pin must be between 2 and 13"),
        (b"W 2 X", b"Unknown pin mode"),
        (b"W 2 h", b"Unknown pin mode"),
    ],
)
def test_write_errors(board: SBArduinoSimulator, command: bytes, message: bytes) -> None:
    assert board.receive(command + b"\n") == error(command, message)
    assert board.pin_mode(2) is PinMode.INPUT


def test_read(board: SBArduinoSimulator) -> None:
    assert board.receive(b"R 2\n") == ok(b"R 2", b"L")
    board.receive(b"W 2 P\n")
    assert board.receive(b"R 2\n") == ok(b"R 2", b"H")
    board.set_input_level(2, False)
    assert board.receive(b"R 2\n") == ok(b"R 2", b"L")
    board.receive(b"W 3 H\n")
    assert board.receive(b"R3\n") == ok(b"R3", b"H")


@pytest.mark.parametrize(
    ("command", "message"),
    [
        (b"R", b"Bad number of arguments"),
        (b"R 2 3", b"Bad number of arguments"),
        (b"R 1", b"pin must be between 2 and 13"),
        (b"R 14", b"pin must be between 2 and 13"),
        (b"R abc", b"pin must be between 2 and 13"),
    ],
)
def test_read_errors(board: SBArduinoSimulator, command: bytes, message: bytes) -> None:
    assert board.receive(command + b"\n") == error(command, message)


# --- A and L ---


def test_analogue_reports_a0_to_a3(board: SBArduinoSimulator) -> None:
    board.set_analogue(14, raw=212)
    board.set_analogue(15, volts=2.5)
    board.set_analogue(17, raw=1023)
    board.set_analogue(18, raw=999)  # A4 is not reported
    assert board.receive(b"A\n") == ok(b"A", b"a0 212", b"a1 512", b"a2 0", b"a3 1023")


def test_led(board: SBArduinoSimulator) -> None:
    board.receive(b"W 13 L\n")
    assert board.receive(b"LH\n") == ok(b"LH")
    assert board.pin_level(13) is True
    assert board.receive(b"LL\n") == ok(b"LL")
    assert board.pin_level(13) is False


def test_led_argument_is_not_trimmed(board: SBArduinoSimulator) -> None:
    assert board.receive(b"L H\n") == error(b"L H", b"Unknown LED State:  H")
    assert board.receive(b"LX\n") == error(b"LX", b"Unknown LED State: X")
    assert board.receive(b"L\n") == error(b"L", b"Unknown LED State: ")


def test_led_on_2019_6_only_writes_the_latch(board: SBArduinoSimulator) -> None:
    board.receive(b"LH\n")  # pin 13 is an input after boot: this is its pull-up
    assert board.pin_mode(13) is PinMode.INPUT_PULLUP


def test_led_on_2019_8_makes_pin_13_an_output(board8: SBArduinoSimulator) -> None:
    board8.receive(b"LX\n")
    assert board8.pin_mode(13) is PinMode.OUTPUT
    board8.receive(b"LH\n")
    assert board8.pin_level(13) is True


# --- T and U ---


def test_ultrasound(board: SBArduinoSimulator) -> None:
    board.set_ultrasound_distance(3, 4, 1.23)
    assert board.ultrasound_echo(3, 4) == 7173
    assert board.receive(b"U 3 4\n") == ok(b"U 3 4", b"1230")
    assert board.receive(b"T 3 4\n") == ok(b"T 3 4", b"7173.00")
    assert board.pin_mode(3) is PinMode.OUTPUT
    assert board.output_level(3) is False
    assert board.pin_mode(4) is PinMode.INPUT


def test_ultrasound_formula_is_single_precision(board: SBArduinoSimulator) -> None:
    board.set_ultrasound_echo(3, 4, 7172)  # 7172 * 0.1715 = 1229.998
    assert board.receive(b"U 3 4\n") == ok(b"U 3 4", b"1229")
    board.set_ultrasound_echo(3, 4, 2345)
    assert board.receive(b"T 3 4\n") == ok(b"T 3 4", b"2345.00")
    assert board.receive(b"U 3 4\n") == ok(b"U 3 4", b"402")


def test_ultrasound_without_echo(board: SBArduinoSimulator) -> None:
    assert board.receive(b"T 5 6\n") == ok(b"T 5 6", b"0.00")
    assert board.receive(b"U 5 6\n") == ok(b"U 5 6", b"0")


def test_ultrasound_range_limits(board: SBArduinoSimulator) -> None:
    board.set_ultrasound_echo(3, 4, 400_000)  # 68600 mm, clamped to unsigned int
    assert board.receive(b"U 3 4\n") == ok(b"U 3 4", b"65535")
    board.set_ultrasound_echo(3, 4, 1_000_001)  # beyond pulseIn's 1 s timeout
    assert board.receive(b"T 3 4\n") == ok(b"T 3 4", b"0.00")
    board.set_ultrasound_distance(3, 4, 100.0)  # beyond what the firmware can report
    assert board.receive(b"U 3 4\n") == ok(b"U 3 4", b"0")


def test_ultrasound_on_one_pin(board: SBArduinoSimulator) -> None:
    board.set_ultrasound_distance(7, 7, 0.5)
    assert board.receive(b"U 7 7\n") == ok(b"U 7 7", b"500")
    assert board.pin_mode(7) is PinMode.INPUT


@pytest.mark.parametrize("letter", [b"T", b"U"])
@pytest.mark.parametrize(
    ("arguments", "message"),
    [
        (b"", b"Arguments required: <trigger> <echo>"),
        (b" 3", b"Arguments required: <trigger> <echo>"),
        (b" 3 4 5", b"Arguments required: <trigger> <echo>"),
        (b" 1 4", b"Pins must be between 2 and 13"),
        (b" 3 14", b"Pins must be between 2 and 13"),
    ],
)
def test_ultrasound_errors(
    board: SBArduinoSimulator, letter: bytes, arguments: bytes, message: bytes
) -> None:
    command = letter + arguments
    assert board.receive(command + b"\n") == error(command, message)


# --- S ---


def test_servo_on_2019_6(board: SBArduinoSimulator) -> None:
    assert board.receive(b"S 3 350\n") == ok(b"S 3 350")
    assert board.receive(b"S 4 150\n") == ok(b"S 4 150")
    assert board.receive(b"S 15 550\n") == ok(b"S 15 550")
    assert board.servo_widths[3:5] == (350, 150)
    assert board.servo_widths[15] == 550
    assert board.servo_pulse_us(3) == pytest.approx(1708.984375)
    assert board.receive(b"S 3 0\n") == ok(b"S 3 0")
    assert board.servo_widths[3] == 0
    assert len(board.servo_widths) == board.SERVO_COUNT == 16


@pytest.mark.parametrize(
    ("command", "message"),
    [
        (b"S", b"Arguments Required: <num> <width>"),
        (b"S 3", b"Arguments Required: <num> <width>"),
        (b"S 3 350 1", b"Arguments Required: <num> <width>"),
        (b"S 16 350", b"Servo out of range"),
        (b"S -1 350", b"Servo out of range"),
        (b"S 3 149", b"Width must be 0 or between 150 and 550"),
        (b"S 3 551", b"Width must be 0 or between 150 and 550"),
        (b"S 16 1", b"Servo out of range"),
    ],
)
def test_servo_errors(board: SBArduinoSimulator, command: bytes, message: bytes) -> None:
    assert board.receive(command + b"\n") == error(command, message)
    assert board.servo_widths == (0,) * 16


@pytest.mark.parametrize("command", [b"S 3 350", b"S", b"S 99 1"])
def test_servo_on_2019_8_is_not_implemented(board8: SBArduinoSimulator, command: bytes) -> None:
    assert board8.receive(command + b"\n") == error(command, b"not implemented")


def test_reboot_turns_the_servos_off(board: SBArduinoSimulator) -> None:
    board.receive(b"S 3 350\n")
    board.open()
    assert board.servo_widths[3] == 0


# --- line handling ---


def test_unknown_command(board: SBArduinoSimulator) -> None:
    assert board.receive(b"X\n") == b"# X\n- Error, unknown command: X\r\n"
    assert board.receive(b"w 2 H\n") == b"# w 2 H\n- Error, unknown command: w\r\n"


def test_empty_line(board: SBArduinoSimulator) -> None:
    assert board.receive(b"\n") == b"# \n- Error, unknown command: \x00\r\n"
    assert board.receive(b"   \t \n") == b"# \n- Error, unknown command: \x00\r\n"


def test_carriage_returns_are_ignored(board: SBArduinoSimulator) -> None:
    assert board.receive(b"W 2 H\r\n") == ok(b"W 2 H")
    assert board.receive(b"W\r 2\r L\r\n") == ok(b"W 2 L")


def test_tabs_and_space_runs_collapse(board: SBArduinoSimulator) -> None:
    assert board.receive(b"W\t\t2   H\n") == ok(b"W 2 H")
    assert board.receive(b"   R 2   \n") == ok(b"R 2", b"H")


def test_nul_clears_the_partial_line(board: SBArduinoSimulator) -> None:
    assert board.receive(b"garbage W 9") == b""
    assert board.pending_input == b"garbage W 9"
    assert board.receive(b"\x00W 2 H\n") == ok(b"W 2 H")
    assert board.pin_mode(9) is PinMode.INPUT


def test_request_id_prefix(board: SBArduinoSimulator) -> None:
    assert board.receive(b"@5 W 2 H\n") == b"# @5 W 2 H\n@5 + OK\r\n"
    assert board.receive(b"@12 R 2\n") == b"# @12 R 2\n@12 > H\r\n@12 + OK\r\n"
    assert board.receive(b"@7 X\n") == b"# @7 X\n@7 - Error, unknown command: X\r\n"
    assert board.receive(b"@7 R 1\n") == b"# @7 R 1\n@7 - Error: pin must be between 2 and 13\r\n"
    assert board.receive(b"@-3 V\n").endswith(b"@-3 > SBDuino GPIO v2019.6.0\r\n@-3 + OK\r\n")


def test_request_id_oddities(board: SBArduinoSimulator) -> None:
    assert board.receive(b"@0 W 2 H\n") == ok(b"@0 W 2 H")  # id 0 means none
    assert board.receive(b"@abc W 2 L\n") == ok(b"@abc W 2 L")
    assert board.receive(b"@70000 V\n").endswith(b"@4464 + OK\r\n")  # a 16-bit int
    assert board.receive(b"@5\n") == b"# @5\n@5 - Error, unknown command: @\r\n"
    assert board.receive(b"@\n") == b"# @\n- Error, unknown command: @\r\n"
    assert board.receive(b"@ V\n") == ok(b"@ V", b"SBDuino GPIO v2019.6.0")


def test_open_reboots_and_forgets_the_partial_line(board: SBArduinoSimulator) -> None:
    board.receive(b"W 2 H\nW 3")
    board.set_analogue(14, raw=9)
    board.set_ultrasound_echo(3, 4, 100)
    assert board.open() == b"# Booted\n# SBDuino GPIO v2019.6.0\r\n"
    assert board.pending_input == b""
    assert board.pin_mode(2) is PinMode.INPUT
    assert board.receive(b" H\n") == b"# H\n- Error, unknown command: H\r\n"
    assert board.receive(b"A\n").startswith(b"# A\n> a0 9\r\n")
    assert board.ultrasound_echo(3, 4) == 100


def test_unplug_and_plug(board: SBArduinoSimulator) -> None:
    board.receive(b"W 2 H\n")
    board.unplug()
    with pytest.raises(SimulatorUnpluggedError):
        board.receive(b"V\n")
    with pytest.raises(SimulatorUnpluggedError):
        board.open()
    board.plug()
    assert board.pin_mode(2) is PinMode.INPUT
    assert board.open().startswith(b"# Booted\n")


FRAGMENTS = [
    b"W 2 H\n",
    b"W 3 P\n",
    b"R 3\n",
    b"A\n",
    b"U 3 4\n",
    b"T 3 4\n",
    b"S 3 350\n",
    b"@5 ",
    b"V\n",
    b"LH\n",
    b"\x00",
    b"\r",
    b"\t",
    b"  ",
    b"\n",
]


def snapshot(board: SBArduinoSimulator) -> tuple[object, ...]:
    return (
        tuple(board.pin_mode(pin) for pin in range(20)),
        tuple(board.output_level(pin) for pin in range(20)),
        board.servo_widths,
        board.pending_input,
    )


def fresh(serial: str) -> SBArduinoSimulator:
    board = SBArduinoSimulator(serial)
    board.open()
    board.set_ultrasound_distance(3, 4, 0.3)
    board.set_analogue(16, raw=123)
    return board


@given(streams(FRAGMENTS), cut_lists)
def test_split_input_gives_the_same_result(data: bytes, cuts: list[int]) -> None:
    whole = fresh("a")
    split = fresh("b")
    assert feed(split, pieces(data, cuts)) == whole.receive(data)
    assert snapshot(split) == snapshot(whole)


@given(streams(FRAGMENTS))
def test_one_byte_at_a_time_gives_the_same_result(data: bytes) -> None:
    whole = fresh("a")
    split = fresh("b")
    assert feed(split, [bytes([byte]) for byte in data]) == whole.receive(data)
    assert snapshot(split) == snapshot(whole)

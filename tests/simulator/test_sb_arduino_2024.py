from __future__ import annotations

import pytest
from hypothesis import given

from j5aio.simulator import (
    SERIAL_SIMULATORS,
    PinMode,
    SBArduino2024Simulator,
    SimulatorUnpluggedError,
    SRRuggeduinoSimulator,
)

from .split_helpers import cut_lists, feed, pieces, streams


@pytest.fixture
def board() -> SBArduino2024Simulator:
    return SBArduino2024Simulator("SB24")


def test_port_description_and_names(board: SBArduino2024Simulator) -> None:
    assert board.baudrate == 115_200
    assert board.resets_on_open
    assert (board.usb_vid, board.usb_pid) == (0x2341, 0x0043)
    assert isinstance(SERIAL_SIMULATORS["sb-arduino-2024"]("x"), SBArduino2024Simulator)
    fw2 = SERIAL_SIMULATORS["sr-arduino-fw2"]("y")
    assert isinstance(fw2, SRRuggeduinoSimulator)
    assert fw2.firmware_version == 2
    assert fw2.serial_number == "y"


def test_no_banner(board: SBArduino2024Simulator) -> None:
    assert board.open() == b""


@pytest.mark.parametrize(
    ("line", "reply"),
    [
        (b"*IDN?", b"SourceBots:Arduino:X:2.0"),
        (b"*STATUS?", b"Yes"),
        (b"*RESET?", b"NACK:Reset not supported"),
        (b"*RESET", b"NACK:Invalid command"),
        (b"", b"NACK:Invalid command"),
        (b"*IDN?\r", b"NACK:Invalid command"),  # CR is not stripped
        (b"*idn?", b"NACK:Invalid command"),
        (b"PIN:3:MODE:GET?\r", b"NACK:Invalid command"),
        (b"PIN:3:MODE:SET:ANALOG", b"NACK:Invalid command"),
        (b"PIN:3:MODE:SET:OUTPUT\r", b"NACK:Invalid command"),
        (b"PIN:3:MODE", b"NACK:Invalid command"),
        (b"PIN:3:DIGITAL:SET", b"NACK:Invalid command"),
        (b"PIN:3:DIGITAL:GET?:1", b"NACK:Invalid command"),
        (b"PIN:3:PWM:SET:5", b"NACK:Invalid command"),
        (b"ULTRASOUND:3:4:MEASURE", b"NACK:Invalid command"),
        (b"ULTRASOUND:3:MEASURE?", b"NACK:Invalid command"),
    ],
)
def test_fixed_replies(board: SBArduino2024Simulator, line: bytes, reply: bytes) -> None:
    assert board.receive(line + b"\n") == reply + b"\n"


def test_modes_read_from_the_registers(board: SBArduino2024Simulator) -> None:
    assert board.receive(b"PIN:3:MODE:GET?\n") == b"INPUT\n"
    assert board.receive(b"PIN:3:MODE:SET:INPUT_PULLUP\n") == b"ACK\n"
    assert board.pin_mode(3) is PinMode.INPUT_PULLUP
    assert board.receive(b"PIN:3:MODE:GET?\n") == b"INPUT_PULLUP\n"
    assert board.receive(b"PIN:3:MODE:SET:OUTPUT\n") == b"ACK\n"
    assert board.receive(b"PIN:3:MODE:GET?\n") == b"OUTPUT\n"
    assert board.output_level(3) is True  # OUTPUT keeps the pull-up's latch
    assert board.receive(b"PIN:3:MODE:SET:INPUT\n") == b"ACK\n"
    assert board.receive(b"PIN:3:MODE:GET?\n") == b"INPUT\n"
    # HIGH written to an input turns its pull-up on, as the registers say.
    assert board.receive(b"PIN:3:DIGITAL:SET:1\n") == b"ACK\n"
    assert board.receive(b"PIN:3:MODE:GET?\n") == b"INPUT_PULLUP\n"


def test_analogue_pins_are_digital_too(board: SBArduino2024Simulator) -> None:
    assert board.receive(b"PIN:19:MODE:SET:OUTPUT\nPIN:19:DIGITAL:SET:1\n") == b"ACK\nACK\n"
    assert board.pin_mode(19) is PinMode.OUTPUT
    assert board.output_level(19) is True
    assert board.receive(b"PIN:19:DIGITAL:GET?\n") == b"1\n"


@pytest.mark.parametrize(("value", "high"), [(b"1", True), (b"0", False), (b"2", False),
                                             (b"", False), (b"1\r", False), (b"HIGH", False)])
def test_digital_set_is_high_only_for_1(
    board: SBArduino2024Simulator, value: bytes, high: bool,
) -> None:
    board.receive(b"PIN:5:MODE:SET:OUTPUT\n")
    assert board.receive(b"PIN:5:DIGITAL:SET:" + value + b"\n") == b"ACK\n"
    assert board.output_level(5) is high


def test_digital_reads_follow_the_outside_world(board: SBArduino2024Simulator) -> None:
    assert board.receive(b"PIN:6:DIGITAL:GET?\n") == b"0\n"
    board.set_input_level(6, True)
    assert board.receive(b"PIN:6:DIGITAL:GET?\n") == b"1\n"
    board.set_input_level(6, None)
    board.receive(b"PIN:6:MODE:SET:INPUT_PULLUP\n")
    assert board.receive(b"PIN:6:DIGITAL:GET?\n") == b"1\n"


def test_analogue_reads_by_channel_or_pin(board: SBArduino2024Simulator) -> None:
    board.set_analogue(14, volts=2.5)
    board.set_analogue(19, raw=1023)
    assert board.receive(b"PIN:14:ANALOG:GET?\n") == b"512\n"
    assert board.receive(b"PIN:0:ANALOG:GET?\n") == b"512\n"
    assert board.receive(b"PIN:5:ANALOG:GET?\n") == b"1023\n"
    assert board.receive(b"PIN:19:ANALOG:GET?\n") == b"1023\n"


def test_pin_fields_parse_as_the_firmware_does(board: SBArduino2024Simulator) -> None:
    # No digits reads as pin 0; pins the Uno lacks are ignored and read low and INPUT.
    assert board.receive(b"PIN:x:MODE:SET:OUTPUT\n") == b"ACK\n"
    assert board.pin_mode(0) is PinMode.OUTPUT
    assert board.receive(b"PIN:65539:MODE:SET:OUTPUT\n") == b"ACK\n"  # 16-bit int: pin 3
    assert board.pin_mode(3) is PinMode.OUTPUT
    assert board.receive(b"PIN:25:MODE:SET:OUTPUT\n") == b"ACK\n"
    assert board.receive(b"PIN:25:MODE:GET?\n") == b"INPUT\n"
    assert board.receive(b"PIN:25:DIGITAL:GET?\n") == b"0\n"


def test_ultrasound(board: SBArduino2024Simulator) -> None:
    board.set_ultrasound_distance(2, 3, 1.23)
    assert board.receive(b"ULTRASOUND:2:3:MEASURE?\n") == b"1230\n"
    assert board.pin_mode(2) is PinMode.OUTPUT
    assert board.output_level(2) is False
    assert board.pin_mode(3) is PinMode.INPUT
    board.set_ultrasound_echo(2, 3, 5800)
    assert board.receive(b"ULTRASOUND:2:3:MEASURE?\n") == b"1000\n"  # 5 * 5800 / 29
    board.set_ultrasound_distance(2, 3, None)
    assert board.receive(b"ULTRASOUND:2:3:MEASURE?\n") == b"0\n"


@pytest.mark.parametrize(
    ("microseconds", "reply"),
    [(32_767, b"5649"), (32_768, b"-5649"), (40_000, b"-4402"), (60_000, b"-954"),
     (60_001, b"0")],
)
def test_long_echoes_wrap_the_16_bit_int(
    board: SBArduino2024Simulator, microseconds: int, reply: bytes,
) -> None:
    board.set_ultrasound_echo(4, 5, microseconds)
    assert board.receive(b"ULTRASOUND:4:5:MEASURE?\n") == reply + b"\n"


def test_a_distance_beyond_the_range_reads_no_echo(board: SBArduino2024Simulator) -> None:
    board.set_ultrasound_distance(4, 5, 20.0)
    assert board.receive(b"ULTRASOUND:4:5:MEASURE?\n") == b"0\n"


def test_reboot_forgets_pins_and_the_partial_line(board: SBArduino2024Simulator) -> None:
    board.receive(b"PIN:7:MODE:SET:OUTPUT\nPIN:7:DIG")
    assert board.pending_input == b"PIN:7:DIG"
    board.set_analogue(15, raw=100)
    assert board.reset() == b""
    assert board.pending_input == b""
    assert board.pin_mode(7) is PinMode.INPUT
    assert board.receive(b"PIN:15:ANALOG:GET?\n") == b"100\n"  # the world stays


def test_unplugged(board: SBArduino2024Simulator) -> None:
    board.receive(b"PIN:7:MODE:SET:OUTPUT\n")
    board.unplug()
    with pytest.raises(SimulatorUnpluggedError):
        board.receive(b"*IDN?\n")
    board.plug()  # powered by USB: it boots
    assert board.pin_mode(7) is PinMode.INPUT
    assert board.receive(b"*IDN?\n") == b"SourceBots:Arduino:X:2.0\n"


FRAGMENTS = [b"*IDN?\n", b"PIN:3:MODE:SET:OUTPUT\n", b"PIN:3:DIGITAL:SET:1\n",
             b"PIN:14:ANALOG:GET?\n", b"ULTRASOUND:2:3:MEASURE?\n", b"PIN:", b":", b"\r", b"\n"]


def snapshot(board: SBArduino2024Simulator) -> list[tuple[PinMode, bool]]:
    return [(board.pin_mode(pin), board.output_level(pin)) for pin in range(20)]


@given(streams(FRAGMENTS), cut_lists)
def test_split_input_gives_the_same_result(data: bytes, cuts: list[int]) -> None:
    whole = SBArduino2024Simulator("a")
    split = SBArduino2024Simulator("b")
    assert feed(split, pieces(data, cuts)) == whole.receive(data)
    assert snapshot(split) == snapshot(whole)
    assert whole.receive(b"\n*IDN?\n").endswith(b"SourceBots:Arduino:X:2.0\n")

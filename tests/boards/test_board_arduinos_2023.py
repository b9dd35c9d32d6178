"""The board classes of the SR Arduino (fw 2) and the SourceBots Arduino (sb2024)."""

from __future__ import annotations

import pytest

from j5aio.backends.hardware.sb import SBArduino2024HardwareBackend
from j5aio.backends.hardware.sr.v4 import SRArduinoHardwareBackend
from j5aio.backends.hardware.transports.memory import SimulatorStream
from j5aio.boards.arduino import AnaloguePin, ArduinoUno
from j5aio.boards.sb import SBArduino2024Board, SBArduinoBoard
from j5aio.boards.sr.v4 import Ruggeduino, SRArduinoBoard
from j5aio.components import LED, GPIOPin, StringCommandComponent, UltrasoundSensor
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.simulator import SBArduino2024Simulator, SRRuggeduinoSimulator

from .board_fakes import FakeSBArduinoBackend, FakeSRArduinoBackend

ALL_DIGITAL = frozenset(
    {GPIOPinMode.DIGITAL_INPUT, GPIOPinMode.DIGITAL_INPUT_PULLUP, GPIOPinMode.DIGITAL_OUTPUT},
)


def test_identities() -> None:
    assert issubclass(SRArduinoBoard, Ruggeduino)
    assert SRArduinoBoard.name == "SR Arduino"
    assert SRArduinoBoard.supported_components() == {
        GPIOPin, LED, StringCommandComponent, UltrasoundSensor,
    }
    assert issubclass(SBArduino2024Board, ArduinoUno)
    assert not issubclass(SBArduino2024Board, SBArduinoBoard)  # no servos on sb2024
    assert SBArduino2024Board.name == "SourceBots Arduino (sb2024)"
    assert SBArduino2024Board.supported_components() == {GPIOPin, LED, UltrasoundSensor}


@pytest.mark.parametrize("board_class", [SRArduinoBoard, SBArduino2024Board])
def test_every_pin_is_digital_and_takes_ultrasound(board_class: type[ArduinoUno]) -> None:
    backend = FakeSRArduinoBackend() if board_class is SRArduinoBoard else FakeSBArduinoBackend()
    board = board_class("B1", backend)
    assert sorted(board.pins.keys()) == list(range(2, 20))
    for number in range(2, 14):
        assert board.pins[number].hardware_modes == ALL_DIGITAL
    for pin in AnaloguePin:
        assert board.pins[pin].hardware_modes == ALL_DIGITAL | {GPIOPinMode.ANALOGUE_INPUT}
    for gpio in board.pins:  # iterating gives the pins, as in j5
        assert gpio.firmware_modes == frozenset({UltrasoundSensor})


def test_the_older_boards_are_unchanged() -> None:
    # the Ruggeduino's firmware 1 drives A0-A5 digitally; the SB 2019 firmware does not
    assert set(SBArduinoBoard.ANALOGUE_PIN_MODES) == {GPIOPinMode.ANALOGUE_INPUT}
    assert ALL_DIGITAL | {GPIOPinMode.ANALOGUE_INPUT} == Ruggeduino.ANALOGUE_PIN_MODES
    for board_class in (Ruggeduino, SBArduinoBoard):
        assert not board_class.ANALOGUE_PIN_FIRMWARE_MODES


async def test_sr_arduino_end_to_end() -> None:
    sim = SRRuggeduinoSimulator("SRA1", firmware_version=2)
    board = await SRArduinoHardwareBackend.from_stream(
        SimulatorStream(sim, time_scale=0), port="sim", serial_number="SRA1", time_scale=0,
    )
    assert isinstance(board, SRArduinoBoard)
    await board.setup()
    a5 = board.pins[AnaloguePin.A5]
    await a5.set_mode(GPIOPinMode.DIGITAL_OUTPUT)
    await a5.digital_write(True)
    assert sim.output_level(19) is True
    sim.set_ultrasound_distance(AnaloguePin.A0, AnaloguePin.A1, 0.5)
    sensor = board.ultrasound_sensors[AnaloguePin.A0, AnaloguePin.A1]
    assert await sensor.distance() == 0.5
    assert await board.command("v") == "SRduino:2"
    await board.close()


async def test_sb2024_end_to_end() -> None:
    sim = SBArduino2024Simulator("SB24")
    board = await SBArduino2024HardwareBackend.from_stream(
        SimulatorStream(sim, time_scale=0), port="sim", serial_number="SB24", time_scale=0,
    )
    assert isinstance(board, SBArduino2024Board)
    await board.setup()
    assert board.serial_number == "SB24"
    sim.set_analogue(AnaloguePin.A2, volts=1.25)
    assert await board.pins[AnaloguePin.A2].analogue_read() == 1.25
    sim.set_ultrasound_echo(2, 3, 50_000)  # wraps the firmware's 16-bit int
    assert await board.ultrasound_sensors[2, 3].distance() is None
    await board.close()

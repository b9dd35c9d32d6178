"""The sync facade of the SR Arduino (fw 2) and SourceBots Arduino (sb2024), on the console."""

from __future__ import annotations

from j5aio import sync
from j5aio.boards.sb import SBArduino2024Board
from j5aio.boards.sr.v4 import SRArduinoBoard
from j5aio.components.gpio_pin import GPIOPinMode

from .sync_fakes import ScriptedConsoleLog, set_up


def test_sr_arduino_in_plain_code() -> None:
    log = ScriptedConsoleLog(["SRduino:2"])
    board = set_up(log, SRArduinoBoard, "SRA1")
    assert isinstance(board, sync.SRArduinoBoard)
    board.pins[14].mode = GPIOPinMode.DIGITAL_OUTPUT  # A0 is a digital pin here
    board.pins[14].digital_write(True)
    assert board.pins[14].last_digital_write is True
    assert any("Set pin 14 state to True" in line for line in log.printed)
    assert board.command.execute("v") == "SRduino:2"


def test_sb2024_ultrasound_in_plain_code() -> None:
    log = ScriptedConsoleLog(["0", "0.25"])
    board = set_up(log, SBArduino2024Board, "SB1")
    assert isinstance(board, sync.SBArduino2024Board)
    sensor = board.ultrasound_sensors[2, 3]
    assert sensor.distance() is None  # 0: no echo
    assert sensor.distance() == 0.25

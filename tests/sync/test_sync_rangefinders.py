"""Both kinds of distance sensor through the sync facade: millimetres and metres alike."""

from __future__ import annotations

from j5aio import sync
from j5aio.boards.sb import SBArduino2024Board

from .sync_fakes import ScriptedConsoleLog, set_up


def test_an_ultrasound_sensor_is_a_rangefinder_read_in_millimetres_too() -> None:
    log = ScriptedConsoleLog(["0.123", "0", "0.5"])
    board = set_up(log, SBArduino2024Board, "SB1")
    assert isinstance(board, sync.SBArduino2024Board)
    sensor = board.ultrasound_sensors[2, 3]
    assert isinstance(sensor, sync.Rangefinder)
    assert sensor.distance_mm() == 123.0
    assert sensor.distance_mm() is None  # 0: no echo
    assert sensor.distance() == 0.5

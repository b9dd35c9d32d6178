"""Boards made by SourceBots."""

from typing import TYPE_CHECKING

from j5aio._lazy import lazy_exports

if TYPE_CHECKING:
    from j5aio.boards.sb.arduino import SBArduinoBoard, UltrasoundSensors
    from j5aio.boards.sb.arduino_2024 import SBArduino2024Board
    from j5aio.boards.sb.servo_board import SBServoBoard

__all__ = ["SBArduino2024Board", "SBArduinoBoard", "SBServoBoard", "UltrasoundSensors"]

if not TYPE_CHECKING:  # the names are imported above for type checkers
    __getattr__, __dir__ = lazy_exports(
        __name__,
        {
            "j5aio.boards.sb.arduino": ["SBArduinoBoard", "UltrasoundSensors"],
            "j5aio.boards.sb.arduino_2024": ["SBArduino2024Board"],
            "j5aio.boards.sb.servo_board": ["SBServoBoard"],
        },
    )

"""Boards made by SourceBots."""

from typing import TYPE_CHECKING

from j5aio._lazy import lazy_exports

if TYPE_CHECKING:
    from j5aio.boards.sb.arduino import SBArduinoBoard as SBArduinoBoard
    from j5aio.boards.sb.arduino import UltrasoundSensors as UltrasoundSensors
    from j5aio.boards.sb.arduino_2024 import SBArduino2024Board as SBArduino2024Board
    from j5aio.boards.sb.servo_board import SBServoBoard as SBServoBoard

if not TYPE_CHECKING:  # type checkers see the names imported above; __all__ is the table's
    __getattr__, __dir__ = lazy_exports(
        __name__,
        {
            "j5aio.boards.sb.arduino": ["SBArduinoBoard", "UltrasoundSensors"],
            "j5aio.boards.sb.arduino_2024": ["SBArduino2024Board"],
            "j5aio.boards.sb.servo_board": ["SBServoBoard"],
        },
    )

"""The version 4 boards of Student Robotics."""

from typing import TYPE_CHECKING

from j5aio._lazy import lazy_exports

if TYPE_CHECKING:
    from j5aio.boards.sr.v4.arduino import SRArduinoBoard as SRArduinoBoard
    from j5aio.boards.sr.v4.motor_board import MotorBoard as MotorBoard
    from j5aio.boards.sr.v4.motor_board_fw4 import MotorBoardFw4 as MotorBoardFw4
    from j5aio.boards.sr.v4.power_board import PowerBoard as PowerBoard
    from j5aio.boards.sr.v4.power_board import PowerOutputGroup as PowerOutputGroup
    from j5aio.boards.sr.v4.power_board import PowerOutputPosition as PowerOutputPosition
    from j5aio.boards.sr.v4.power_board_fw4 import BoardResetInterface as BoardResetInterface
    from j5aio.boards.sr.v4.power_board_fw4 import PowerBoardFw4 as PowerBoardFw4
    from j5aio.boards.sr.v4.power_board_fw4 import PowerBoardOutput as PowerBoardOutput
    from j5aio.boards.sr.v4.power_board_fw4 import PowerBoardOutputGroup as PowerBoardOutputGroup
    from j5aio.boards.sr.v4.ruggeduino import Ruggeduino as Ruggeduino
    from j5aio.boards.sr.v4.servo_board import ServoBoard as ServoBoard
    from j5aio.boards.sr.v4.servo_board_fw4 import ServoBoardFw4 as ServoBoardFw4

if not TYPE_CHECKING:  # type checkers see the names imported above; __all__ is the table's
    __getattr__, __dir__ = lazy_exports(
        __name__,
        {
            "j5aio.boards.sr.v4.arduino": ["SRArduinoBoard"],
            "j5aio.boards.sr.v4.motor_board": ["MotorBoard"],
            "j5aio.boards.sr.v4.motor_board_fw4": ["MotorBoardFw4"],
            "j5aio.boards.sr.v4.power_board": [
                "PowerBoard",
                "PowerOutputGroup",
                "PowerOutputPosition",
            ],
            "j5aio.boards.sr.v4.power_board_fw4": [
                "BoardResetInterface",
                "PowerBoardFw4",
                "PowerBoardOutput",
                "PowerBoardOutputGroup",
            ],
            "j5aio.boards.sr.v4.ruggeduino": ["Ruggeduino"],
            "j5aio.boards.sr.v4.servo_board": ["ServoBoard"],
            "j5aio.boards.sr.v4.servo_board_fw4": ["ServoBoardFw4"],
        },
    )

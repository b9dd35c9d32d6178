"""The version 4 boards of Student Robotics."""

from typing import TYPE_CHECKING

from j5aio._lazy import lazy_exports

if TYPE_CHECKING:
    from j5aio.boards.sr.v4.arduino import SRArduinoBoard
    from j5aio.boards.sr.v4.motor_board import MotorBoard
    from j5aio.boards.sr.v4.motor_board_fw4 import MotorBoardFw4
    from j5aio.boards.sr.v4.power_board import PowerBoard, PowerOutputGroup, PowerOutputPosition
    from j5aio.boards.sr.v4.power_board_fw4 import (
        BoardResetInterface,
        PowerBoardFw4,
        PowerBoardOutput,
        PowerBoardOutputGroup,
    )
    from j5aio.boards.sr.v4.ruggeduino import Ruggeduino
    from j5aio.boards.sr.v4.servo_board import ServoBoard
    from j5aio.boards.sr.v4.servo_board_fw4 import ServoBoardFw4

__all__ = [
    "BoardResetInterface",
    "MotorBoard",
    "MotorBoardFw4",
    "PowerBoard",
    "PowerBoardFw4",
    "PowerBoardOutput",
    "PowerBoardOutputGroup",
    "PowerOutputGroup",
    "PowerOutputPosition",
    "Ruggeduino",
    "SRArduinoBoard",
    "ServoBoard",
    "ServoBoardFw4",
]

if not TYPE_CHECKING:  # the names are imported above for type checkers
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

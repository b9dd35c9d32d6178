"""Console backends of the Student Robotics v4 boards."""

from typing import TYPE_CHECKING

from j5aio._lazy import lazy_exports

if TYPE_CHECKING:
    from j5aio.backends.console.sr.v4.arduino import SRArduinoConsoleBackend
    from j5aio.backends.console.sr.v4.motor_board import SRV4MotorBoardConsoleBackend
    from j5aio.backends.console.sr.v4.motor_board_fw4 import SRV4MotorBoardFw4ConsoleBackend
    from j5aio.backends.console.sr.v4.power_board import SRV4PowerBoardConsoleBackend
    from j5aio.backends.console.sr.v4.power_board_fw4 import SRV4PowerBoardFw4ConsoleBackend
    from j5aio.backends.console.sr.v4.ruggeduino import SRV4RuggeduinoConsoleBackend
    from j5aio.backends.console.sr.v4.servo_board import SRV4ServoBoardConsoleBackend
    from j5aio.backends.console.sr.v4.servo_board_fw4 import (
        SBServoBoardConsoleBackend,
        SRV4ServoBoardFw4ConsoleBackend,
    )

__all__ = [
    "SBServoBoardConsoleBackend",
    "SRArduinoConsoleBackend",
    "SRV4MotorBoardConsoleBackend",
    "SRV4MotorBoardFw4ConsoleBackend",
    "SRV4PowerBoardConsoleBackend",
    "SRV4PowerBoardFw4ConsoleBackend",
    "SRV4RuggeduinoConsoleBackend",
    "SRV4ServoBoardConsoleBackend",
    "SRV4ServoBoardFw4ConsoleBackend",
]

if not TYPE_CHECKING:  # the names are imported above for type checkers
    __getattr__, __dir__ = lazy_exports(
        __name__,
        {
            "j5aio.backends.console.sr.v4.arduino": ["SRArduinoConsoleBackend"],
            "j5aio.backends.console.sr.v4.motor_board": ["SRV4MotorBoardConsoleBackend"],
            "j5aio.backends.console.sr.v4.motor_board_fw4": ["SRV4MotorBoardFw4ConsoleBackend"],
            "j5aio.backends.console.sr.v4.power_board": ["SRV4PowerBoardConsoleBackend"],
            "j5aio.backends.console.sr.v4.power_board_fw4": ["SRV4PowerBoardFw4ConsoleBackend"],
            "j5aio.backends.console.sr.v4.ruggeduino": ["SRV4RuggeduinoConsoleBackend"],
            "j5aio.backends.console.sr.v4.servo_board": ["SRV4ServoBoardConsoleBackend"],
            "j5aio.backends.console.sr.v4.servo_board_fw4": [
                "SBServoBoardConsoleBackend",
                "SRV4ServoBoardFw4ConsoleBackend",
            ],
        },
    )

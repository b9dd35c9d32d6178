"""Console backends of the Student Robotics v4 boards."""

from typing import TYPE_CHECKING

from j5aio._lazy import lazy_exports

if TYPE_CHECKING:
    from j5aio.backends.console.sr.v4.arduino import (
        SRArduinoConsoleBackend as SRArduinoConsoleBackend,
    )
    from j5aio.backends.console.sr.v4.motor_board import (
        SRV4MotorBoardConsoleBackend as SRV4MotorBoardConsoleBackend,
    )
    from j5aio.backends.console.sr.v4.motor_board_fw4 import (
        SRV4MotorBoardFw4ConsoleBackend as SRV4MotorBoardFw4ConsoleBackend,
    )
    from j5aio.backends.console.sr.v4.power_board import (
        SRV4PowerBoardConsoleBackend as SRV4PowerBoardConsoleBackend,
    )
    from j5aio.backends.console.sr.v4.power_board_fw4 import (
        SRV4PowerBoardFw4ConsoleBackend as SRV4PowerBoardFw4ConsoleBackend,
    )
    from j5aio.backends.console.sr.v4.ruggeduino import (
        SRV4RuggeduinoConsoleBackend as SRV4RuggeduinoConsoleBackend,
    )
    from j5aio.backends.console.sr.v4.servo_board import (
        SRV4ServoBoardConsoleBackend as SRV4ServoBoardConsoleBackend,
    )
    from j5aio.backends.console.sr.v4.servo_board_fw4 import (
        SBServoBoardConsoleBackend as SBServoBoardConsoleBackend,
    )
    from j5aio.backends.console.sr.v4.servo_board_fw4 import (
        SRV4ServoBoardFw4ConsoleBackend as SRV4ServoBoardFw4ConsoleBackend,
    )

if not TYPE_CHECKING:  # type checkers see the names imported above; __all__ is the table's
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

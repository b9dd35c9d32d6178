"""Hardware backends for the Student Robotics v4 kit."""

from typing import TYPE_CHECKING

from j5aio._lazy import lazy_exports

if TYPE_CHECKING:
    from j5aio.backends.hardware.sr.v4.arduino import SRArduinoHardwareBackend
    from j5aio.backends.hardware.sr.v4.motor_board import (
        SRV4MotorBoardHardwareBackend,
        SRV4MotorBoardJ5ScaleHardwareBackend,
    )
    from j5aio.backends.hardware.sr.v4.motor_board_fw4 import SRV4MotorBoardFw4HardwareBackend
    from j5aio.backends.hardware.sr.v4.motor_identify import (
        MotorBoardIdentity,
        identify_motor_board,
    )
    from j5aio.backends.hardware.sr.v4.power_board import SRV4PowerBoardHardwareBackend
    from j5aio.backends.hardware.sr.v4.power_board_fw4 import SRV4PowerBoardFw4HardwareBackend
    from j5aio.backends.hardware.sr.v4.ruggeduino import SRV4RuggeduinoHardwareBackend
    from j5aio.backends.hardware.sr.v4.servo_board import SRV4ServoBoardHardwareBackend
    from j5aio.backends.hardware.sr.v4.servo_board_fw4 import (
        SERVO_FW4_BACKENDS,
        SBServoBoardHardwareBackend,
        SRV4ServoBoardFw4HardwareBackend,
    )

__all__ = [
    "SERVO_FW4_BACKENDS",
    "MotorBoardIdentity",
    "SBServoBoardHardwareBackend",
    "SRArduinoHardwareBackend",
    "SRV4MotorBoardFw4HardwareBackend",
    "SRV4MotorBoardHardwareBackend",
    "SRV4MotorBoardJ5ScaleHardwareBackend",
    "SRV4PowerBoardFw4HardwareBackend",
    "SRV4PowerBoardHardwareBackend",
    "SRV4RuggeduinoHardwareBackend",
    "SRV4ServoBoardFw4HardwareBackend",
    "SRV4ServoBoardHardwareBackend",
    "identify_motor_board",
]

if not TYPE_CHECKING:  # the names are imported above for type checkers
    __getattr__, __dir__ = lazy_exports(
        __name__,
        {
            "j5aio.backends.hardware.sr.v4.arduino": ["SRArduinoHardwareBackend"],
            "j5aio.backends.hardware.sr.v4.motor_board": [
                "SRV4MotorBoardHardwareBackend",
                "SRV4MotorBoardJ5ScaleHardwareBackend",
            ],
            "j5aio.backends.hardware.sr.v4.motor_board_fw4": ["SRV4MotorBoardFw4HardwareBackend"],
            "j5aio.backends.hardware.sr.v4.motor_identify": [
                "MotorBoardIdentity",
                "identify_motor_board",
            ],
            "j5aio.backends.hardware.sr.v4.power_board": ["SRV4PowerBoardHardwareBackend"],
            "j5aio.backends.hardware.sr.v4.power_board_fw4": ["SRV4PowerBoardFw4HardwareBackend"],
            "j5aio.backends.hardware.sr.v4.ruggeduino": ["SRV4RuggeduinoHardwareBackend"],
            "j5aio.backends.hardware.sr.v4.servo_board": ["SRV4ServoBoardHardwareBackend"],
            "j5aio.backends.hardware.sr.v4.servo_board_fw4": [
                "SBServoBoardHardwareBackend",
                "SERVO_FW4_BACKENDS",
                "SRV4ServoBoardFw4HardwareBackend",
            ],
        },
    )

"""j5aio's own board kinds and named kits, as :mod:`j5aio.board_kinds` registers them.

A new board of j5aio's is added here with one :class:`~j5aio.board_kinds.BoardKind`
entry in :func:`entries` (and a new kit with one :class:`~j5aio.board_kinds.KitDefinition`).
"""

from __future__ import annotations

from j5aio.backends.console.sb.arduino import SBArduinoConsoleBackend
from j5aio.backends.console.sr.v4 import (
    SRV4MotorBoardConsoleBackend,
    SRV4PowerBoardConsoleBackend,
    SRV4RuggeduinoConsoleBackend,
    SRV4ServoBoardConsoleBackend,
)
from j5aio.backends.hardware.sb.arduino import SBArduinoHardwareBackend
from j5aio.backends.hardware.sr.v4.motor_board import SRV4MotorBoardHardwareBackend
from j5aio.backends.hardware.sr.v4.power_board import SRV4PowerBoardHardwareBackend
from j5aio.backends.hardware.sr.v4.ruggeduino import SRV4RuggeduinoHardwareBackend
from j5aio.backends.hardware.sr.v4.servo_board import SRV4ServoBoardHardwareBackend
from j5aio.board_kinds import DEFAULT_KIT, BoardKind, KitDefinition, SimulatorEntry
from j5aio.boards.sb import SBArduinoBoard
from j5aio.boards.sr.v4 import MotorBoard, PowerBoard, Ruggeduino, ServoBoard
from j5aio.simulator.sb_arduino_2019 import SBArduinoSimulator
from j5aio.simulator.sr_motor_fw3 import SRMotorBoardFw3Simulator
from j5aio.simulator.sr_power_fw3 import SRPowerBoardFw3Simulator
from j5aio.simulator.sr_ruggeduino_fw1 import SRRuggeduinoSimulator
from j5aio.simulator.sr_servo_fw2 import SRServoBoardFw2Simulator

__all__ = ["entries"]


def entries() -> list[BoardKind | KitDefinition]:
    """j5aio's board kinds, in the order discovery and listing try them, then its kits.

    The SourceBots Arduino comes before the Ruggeduino: both use the same USB IDs, and
    the SourceBots firmware announces itself when the port opens, while the Ruggeduino
    has to be asked.
    """
    return [
        BoardKind(
            name="sr-v4-power-fw3",
            board=PowerBoard,
            description="SR v4 power board, firmware 3 (USB)",
            hardware=SRV4PowerBoardHardwareBackend,
            console=SRV4PowerBoardConsoleBackend,
            simulators=(
                SimulatorEntry(
                    "sr-power", SRPowerBoardFw3Simulator,
                    "SR v4 power board, firmware 3 (USB control transfers)", "SIMPB",
                ),
            ),
        ),
        BoardKind(
            name="sr-v4-motor-fw3",
            board=MotorBoard,
            description="SR v4 motor board, firmware 3 (serial, 1 Mbaud)",
            hardware=SRV4MotorBoardHardwareBackend,
            console=SRV4MotorBoardConsoleBackend,
            simulators=(
                SimulatorEntry(
                    "sr-motor", SRMotorBoardFw3Simulator,
                    "SR v4 motor board, firmware 3 (1 Mbaud)", "SIMMB",
                ),
            ),
            # Its probe (a resync byte and a version query at 1 Mbaud) is quick, and
            # nothing sent at 115200 baud can reach it as a motor command first.
            identify_order=10,
        ),
        BoardKind(
            name="sr-v4-servo-fw2",
            board=ServoBoard,
            description="SR v4 servo board, firmware 2 (USB)",
            hardware=SRV4ServoBoardHardwareBackend,
            console=SRV4ServoBoardConsoleBackend,
            simulators=(
                SimulatorEntry(
                    "sr-servo", SRServoBoardFw2Simulator,
                    "SR v4 servo board, firmware 2 (USB control transfers)", "SIMSB",
                ),
            ),
        ),
        BoardKind(
            name="sb-arduino-2019",
            board=SBArduinoBoard,
            description="SourceBots Arduino, 2019 firmware (serial, 115200 baud)",
            hardware=SBArduinoHardwareBackend,
            console=SBArduinoConsoleBackend,
            simulators=(
                SimulatorEntry(
                    "sb-arduino", SBArduinoSimulator,
                    "SourceBots Arduino, 2019 firmware (115200 baud)", "SIMSBA",
                ),
            ),
            identify_order=50,
        ),
        BoardKind(
            name="sr-ruggeduino-fw1",
            board=Ruggeduino,
            description="SR Ruggeduino, firmware 1 (serial, 115200 baud)",
            hardware=SRV4RuggeduinoHardwareBackend,
            console=SRV4RuggeduinoConsoleBackend,
            simulators=(
                SimulatorEntry(
                    "sr-ruggeduino", SRRuggeduinoSimulator,
                    "SR Ruggeduino, firmware 1 (115200 baud)", "SIMRD",
                ),
            ),
            identify_order=60,
        ),
        KitDefinition(
            DEFAULT_KIT,
            "one power board, two motor boards, one servo board and a SourceBots Arduino",
            {"sr-power": 1, "sr-motor": 2, "sr-servo": 1, "sb-arduino": 1},
        ),
        KitDefinition(
            "sr2019",
            "Student Robotics' kit of 2019 to 2022: SR v4 power (fw 3), motor (fw 3) and "
            "servo (fw 2) boards and a Ruggeduino (fw 1)",
            {"sr-power": 1, "sr-motor": 1, "sr-servo": 1, "sr-ruggeduino": 1},
        ),
        KitDefinition(
            "sb2019",
            "SourceBots' kit of 2019 to 2023: SR v4 power (fw 3), motor (fw 3) and servo "
            "(fw 2) boards and a SourceBots Arduino (2019 firmware)",
            {"sr-power": 1, "sr-motor": 1, "sr-servo": 1, "sb-arduino": 1},
        ),
    ]

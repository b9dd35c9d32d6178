"""j5aio's own board kinds and named kits, as :mod:`j5aio.board_kinds` registers them.

A new board of j5aio's is added here with one :class:`~j5aio.board_kinds.BoardKind`
entry in :func:`entries` (and a new kit with one :class:`~j5aio.board_kinds.KitDefinition`).
"""

from __future__ import annotations

from j5aio.backends._kind_types import (
    DEFAULT_KIT,
    BoardKind,
    KitDefinition,
    SimulatorClass,
    SimulatorEntry,
)
from j5aio.boards.camera import CameraBoard
from j5aio.boards.sb import SBArduino2024Board, SBArduinoBoard, SBServoBoard
from j5aio.boards.sr.kch import KCHBoard
from j5aio.boards.sr.v4 import (
    MotorBoard,
    MotorBoardFw4,
    PowerBoard,
    PowerBoardFw4,
    Ruggeduino,
    ServoBoard,
    ServoBoardFw4,
    SRArduinoBoard,
)

__all__ = ["entries"]


def _sim(path: str, *, serial_keyword: str | None = None, **keywords: object) -> SimulatorClass:
    """A simulator class of :mod:`j5aio.simulator`, by its path there (imported on first use)."""
    return SimulatorClass(f"j5aio.simulator.{path}", serial_keyword=serial_keyword, **keywords)


def _simulated(name: str) -> str:
    """The import path of a simulated backend of :mod:`j5aio.simulator.sim_backends`."""
    return f"j5aio.simulator.sim_backends:{name}"


def _simulated_2023(name: str) -> str:
    """The import path of a simulated backend of :mod:`j5aio.simulator.sim_backends_2023`."""
    return f"j5aio.simulator.sim_backends_2023:{name}"


def entries() -> list[BoardKind | KitDefinition]:
    """j5aio's board kinds, in the order discovery and listing try them, then its kits.

    The Arduinos share their USB IDs. The sb2024 firmware is asked first (see its
    entry); the SourceBots 2019 firmware comes before the Ruggeduino, since it announces
    itself when the port opens, while the Ruggeduino has to be asked. Of today's boards,
    those that share USB IDs with an older generation (power 1BDA:0010, servo 1BDA:0011
    as CDC serial; the motor board's FTDI adapter; the Arduinos) are told apart by what
    they answer.
    """
    return [
        BoardKind(
            name="sr-v4-power-fw3",
            board=PowerBoard,
            description="SR v4 power board, firmware 3 (USB)",
            hardware="j5aio.backends.hardware.sr.v4.power_board:SRV4PowerBoardHardwareBackend",
            console="j5aio.backends.console.sr.v4:SRV4PowerBoardConsoleBackend",
            simulated=_simulated("SRV4PowerBoardSimulatedBackend"),
            simulators=(
                SimulatorEntry(
                    "sr-power", _sim("sr_power_fw3:SRPowerBoardFw3Simulator"),
                    "SR v4 power board, firmware 3 (USB control transfers)", "SIMPB",
                    transport="usb",
                ),
            ),
        ),
        BoardKind(
            name="sr-v4-motor-fw3",
            board=MotorBoard,
            description="SR v4 motor board, firmware 3 (serial, 1 Mbaud)",
            hardware="j5aio.backends.hardware.sr.v4.motor_board:SRV4MotorBoardHardwareBackend",
            console="j5aio.backends.console.sr.v4:SRV4MotorBoardConsoleBackend",
            simulated=_simulated("SRV4MotorBoardSimulatedBackend"),
            simulators=(
                SimulatorEntry(
                    "sr-motor", _sim("sr_motor_fw3:SRMotorBoardFw3Simulator"),
                    "SR v4 motor board, firmware 3 (1 Mbaud)", "SIMMB",
                    transport="serial",
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
            hardware="j5aio.backends.hardware.sr.v4.servo_board:SRV4ServoBoardHardwareBackend",
            console="j5aio.backends.console.sr.v4:SRV4ServoBoardConsoleBackend",
            simulated=_simulated("SRV4ServoBoardSimulatedBackend"),
            simulators=(
                SimulatorEntry(
                    "sr-servo", _sim("sr_servo_fw2:SRServoBoardFw2Simulator"),
                    "SR v4 servo board, firmware 2 (USB control transfers)", "SIMSB",
                    transport="usb",
                ),
            ),
        ),
        BoardKind(
            name="sb-arduino-2019",
            board=SBArduinoBoard,
            description="SourceBots Arduino, 2019 firmware (serial, 115200 baud)",
            hardware="j5aio.backends.hardware.sb.arduino:SBArduinoHardwareBackend",
            console="j5aio.backends.console.sb.arduino:SBArduinoConsoleBackend",
            simulated=_simulated("SBArduinoSimulatedBackend"),
            simulators=(
                SimulatorEntry(
                    "sb-arduino", _sim("sb_arduino_2019:SBArduinoSimulator"),
                    "SourceBots Arduino, 2019 firmware (115200 baud)", "SIMSBA",
                    transport="serial",
                ),
            ),
            identify_order=50,
        ),
        BoardKind(
            name="sr-ruggeduino-fw1",
            board=Ruggeduino,
            description="SR Ruggeduino, firmware 1 (serial, 115200 baud)",
            hardware="j5aio.backends.hardware.sr.v4.ruggeduino:SRV4RuggeduinoHardwareBackend",
            console="j5aio.backends.console.sr.v4:SRV4RuggeduinoConsoleBackend",
            simulated=_simulated("SRV4RuggeduinoSimulatedBackend"),
            simulators=(
                SimulatorEntry(
                    "sr-ruggeduino", _sim("sr_ruggeduino_fw1:SRRuggeduinoSimulator"),
                    "SR Ruggeduino, firmware 1 (115200 baud)", "SIMRD",
                    transport="serial",
                ),
            ),
            identify_order=60,
        ),
        BoardKind(
            name="sr-v4-power-fw4",
            board=PowerBoardFw4,
            description="SR v4 power board, firmware 4.4 (CDC serial)",
            hardware="j5aio.backends.hardware.sr.v4.power_board_fw4:SRV4PowerBoardFw4HardwareBackend",
            console="j5aio.backends.console.sr.v4:SRV4PowerBoardFw4ConsoleBackend",
            simulated=_simulated_2023("SRV4PowerBoardFw4SimulatedBackend"),
            simulators=(
                SimulatorEntry(
                    "sr-power-fw4", _sim("sr_power_fw4:SRPowerBoardFw4Simulator"),
                    "SR v4 power board, firmware 4.4 (CDC serial)", "SIMPB",
                    transport="serial",
                ),
            ),
            identify_order=20,
        ),
        BoardKind(
            name="sr-v4-motor-fw4",
            board=MotorBoardFw4,
            description="SR v4 motor board, firmware 4.4 / 4.5 (serial, 115200 baud)",
            hardware="j5aio.backends.hardware.sr.v4.motor_board_fw4:SRV4MotorBoardFw4HardwareBackend",
            console="j5aio.backends.console.sr.v4:SRV4MotorBoardFw4ConsoleBackend",
            simulated=_simulated_2023("SRV4MotorBoardFw4SimulatedBackend"),
            simulators=(
                SimulatorEntry(
                    "sr-motor-fw4", _sim("sr_motor_fw4:SRMotorBoardFw4Simulator"),
                    "SR v4 motor board, firmware 4.4 (115200 baud)", "SIMMB",
                    transport="serial",
                ),
                SimulatorEntry(
                    "sb-motor-fw4",
                    _sim("sr_motor_fw4:SRMotorBoardFw4Simulator", version="4.5.0"),
                    "SR v4 motor board, SourceBots firmware 4.5 (115200 baud)", "SIMMB",
                    transport="serial",
                ),
            ),
            # Its probe (a NUL, then *IDN? at 115200 baud) is harmless to a firmware 3
            # board, which takes the NUL as a resync and ignores the rest.
            identify_order=12,
        ),
        BoardKind(
            name="sr-v4-servo-fw4",
            board=ServoBoardFw4,
            description="SR v4 servo board, firmware 4.3 (CDC serial, 12 servos)",
            hardware="j5aio.backends.hardware.sr.v4.servo_board_fw4:SRV4ServoBoardFw4HardwareBackend",
            console="j5aio.backends.console.sr.v4:SRV4ServoBoardFw4ConsoleBackend",
            simulated=_simulated_2023("SRV4ServoBoardFw4SimulatedBackend"),
            simulators=(
                SimulatorEntry(
                    "sr-servo-fw4", _sim("sr_servo_fw4:SRServoBoardFw4Simulator"),
                    "SR v4 servo board, firmware 4.3 (CDC serial, 12 servos)", "SIMSB",
                    transport="serial",
                ),
            ),
            identify_order=30,
        ),
        BoardKind(
            name="sb-servo-fw4",
            board=SBServoBoard,
            description="SR v4 servo board, SourceBots firmware 4.4 (CDC serial, 8 servos)",
            hardware="j5aio.backends.hardware.sr.v4.servo_board_fw4:SBServoBoardHardwareBackend",
            console="j5aio.backends.console.sr.v4:SBServoBoardConsoleBackend",
            simulated=_simulated_2023("SBServoBoardSimulatedBackend"),
            simulators=(
                SimulatorEntry(
                    "sb-servo-fw4", _sim("sr_servo_fw4:SBServoBoardFw4Simulator"),
                    "SR v4 servo board, SourceBots firmware 4.4 (8 servos)", "SIMSB",
                    transport="serial",
                ),
            ),
            identify_order=31,
        ),
        BoardKind(
            name="sr-arduino-fw2",
            board=SRArduinoBoard,
            description="SR Arduino, firmware 2 (serial, 115200 baud)",
            hardware="j5aio.backends.hardware.sr.v4.arduino:SRArduinoHardwareBackend",
            console="j5aio.backends.console.sr.v4:SRArduinoConsoleBackend",
            simulated=_simulated_2023("SRArduinoSimulatedBackend"),
            simulators=(
                SimulatorEntry(
                    "sr-arduino-fw2",
                    _sim("sr_ruggeduino_fw1:SRRuggeduinoSimulator", firmware_version=2),
                    "SR Arduino, firmware 2 (115200 baud)", "SIMSRA",
                    transport="serial",
                ),
            ),
            identify_order=55,
        ),
        BoardKind(
            name="sb-arduino-2024",
            board=SBArduino2024Board,
            description="SourceBots Arduino, sb2024 firmware 2.0 (serial, 115200 baud)",
            hardware="j5aio.backends.hardware.sb.arduino_2024:SBArduino2024HardwareBackend",
            console="j5aio.backends.console.sb.arduino_2024:SBArduino2024ConsoleBackend",
            simulated=_simulated_2023("SBArduino2024SimulatedBackend"),
            simulators=(
                SimulatorEntry(
                    "sb-arduino-2024", _sim("sb_arduino_2024:SBArduino2024Simulator"),
                    "SourceBots Arduino, sb2024 firmware 2.0 (115200 baud)", "SIMSBA",
                    transport="serial",
                ),
            ),
            # First of the Arduinos: every other Arduino firmware answers its probe
            # (``*IDN?`` and a line end) at once, with a boot banner, an error or an empty
            # line per byte, while this silent line-based firmware would leave their
            # probes (waiting for a banner; ``v`` with no line end) to time out.
            identify_order=45,
        ),
        BoardKind(
            name="sr-kch",
            board=KCHBoard,
            description="SR KCH, the Raspberry Pi HAT (GPIO: user and start LEDs)",
            hardware="j5aio.backends.hardware.sr.kch:KCHHardwareBackend",
            console="j5aio.backends.console.sr.kch:KCHConsoleBackend",
            simulators=(
                SimulatorEntry(
                    "kch", _sim("kch:KCHSimulator", serial_keyword="serial_number"),
                    "SR KCH (mock GPIO pins)", "SIMKCH",
                    transport="other",
                ),
            ),
            simulated="j5aio.simulator.kch:KCHSimulatedBackend",
        ),
        BoardKind(
            name="camera",
            board=CameraBoard,
            description="a webcam finding AprilTag markers (the optional extra j5aio[vision])",
            hardware="j5aio.backends.camera.opencv:OpenCVCameraBackend",
            console="j5aio.backends.console.camera:CameraConsoleBackend",
            # Every simulated kit has the robot's camera in its arena (kit.camera).
            simulated="j5aio.simulator.camera:SimulatedCameraBackend",
        ),
        KitDefinition(
            DEFAULT_KIT,
            "one power board, two motor boards, one servo board and a SourceBots Arduino",
            {"sr-power": 1, "sr-motor": 2, "sr-servo": 1, "sb-arduino": 1},
            wiring={"sr-motor": ("H0", "H1"), "sr-servo": ("L0",)},
        ),
        KitDefinition(
            "sr2019",
            "Student Robotics' kit of 2019 to 2022: SR v4 power (fw 3), motor (fw 3) and "
            "servo (fw 2) boards and a Ruggeduino (fw 1)",
            {"sr-power": 1, "sr-motor": 1, "sr-servo": 1, "sr-ruggeduino": 1},
            wiring={"sr-motor": ("H0",), "sr-servo": ("L0",)},
        ),
        KitDefinition(
            "sb2019",
            "SourceBots' kit of 2019 to 2023: SR v4 power (fw 3), motor (fw 3) and servo "
            "(fw 2) boards and a SourceBots Arduino (2019 firmware)",
            {"sr-power": 1, "sr-motor": 1, "sr-servo": 1, "sb-arduino": 1},
            wiring={"sr-motor": ("H0",), "sr-servo": ("L0",)},
        ),
        KitDefinition(
            "sr2023",
            "Student Robotics' kit from 2023: SR v4 power (fw 4.4), motor (fw 4.4) and servo "
            "(fw 4.3) boards, an SR Arduino (fw 2) and the KCH on the Raspberry Pi",
            {
                "sr-power-fw4": 1, "sr-motor-fw4": 1, "sr-servo-fw4": 1,
                "sr-arduino-fw2": 1, "kch": 1,
            },
            wiring={"sr-motor-fw4": ("H0",), "sr-servo-fw4": ("L0",)},
        ),
        KitDefinition(
            "sb2024",
            "SourceBots' kit from 2024: SR v4 power (fw 4.4), motor (SourceBots fw 4.5) "
            "and servo (SourceBots fw 4.4, 8 servos) boards, a SourceBots Arduino "
            "(sb2024 firmware) and the KCH on the Raspberry Pi (sbot drives its LEDs)",
            {
                "sr-power-fw4": 1, "sb-motor-fw4": 1, "sb-servo-fw4": 1,
                "sb-arduino-2024": 1, "kch": 1,
            },
            wiring={"sb-motor-fw4": ("H0",), "sb-servo-fw4": ("L0",)},
        ),
    ]

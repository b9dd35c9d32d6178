"""j5aio's own board kinds and named kits, as :mod:`j5aio.board_kinds` registers them.

A new board of j5aio's is added here with one :class:`~j5aio.board_kinds.BoardKind`
entry in :func:`entries` (and a new kit with one :class:`~j5aio.board_kinds.KitDefinition`).
A board whose backends are named after one stem (``<stem>HardwareBackend`` and so on)
is entered with ``_kind``, and its simulators with ``_simulator``.
"""

from __future__ import annotations

from j5aio.backends._kind_types import (
    DEFAULT_KIT,
    BoardKind,
    KitDefinition,
    SimulatorClass,
    SimulatorEntry,
    SimulatorTransport,
)

__all__ = ["entries"]


def _sim(path: str, *, serial_keyword: str | None = None, **keywords: object) -> SimulatorClass:
    """A simulator class of :mod:`j5aio.simulator`, by its path there (imported on first use)."""
    return SimulatorClass(f"j5aio.simulator.{path}", serial_keyword=serial_keyword, **keywords)


def _simulator(
    name: str,
    path: str,
    description: str,
    serial_prefix: str,
    transport: SimulatorTransport,
    *,
    serial_keyword: str | None = None,
    **keywords: object,
) -> SimulatorEntry:
    """A simulator entry whose factory is a class of :mod:`j5aio.simulator` (see :func:`_sim`)."""
    factory = _sim(path, serial_keyword=serial_keyword, **keywords)
    return SimulatorEntry(name, factory, description, serial_prefix, transport=transport)


def _kind(
    name: str,
    board: str,
    description: str,
    stem: str,
    modules: tuple[str, str, str],
    *simulators: SimulatorEntry,
    identify_order: int = BoardKind.identify_order,
) -> BoardKind:
    """A board kind whose three backends are named after one stem.

    Its board class is named by its path below ``j5aio.boards`` (imported when first
    read: a program imports the board classes of the kit it uses only). Its backends are
    ``<stem>HardwareBackend``, ``<stem>ConsoleBackend`` and ``<stem>SimulatedBackend``,
    in the modules ``modules`` names below ``j5aio.backends.hardware``,
    ``j5aio.backends.console`` and ``j5aio.simulator``.
    """
    hardware, console, simulated = modules
    return BoardKind(
        name=name,
        board=f"j5aio.boards.{board}",
        description=description,
        hardware=f"j5aio.backends.hardware.{hardware}:{stem}HardwareBackend",
        console=f"j5aio.backends.console.{console}:{stem}ConsoleBackend",
        simulated=f"j5aio.simulator.{simulated}:{stem}SimulatedBackend",
        simulators=simulators,
        identify_order=identify_order,
    )


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
        _kind(
            "sr-v4-power-fw3", "sr.v4.power_board:PowerBoard",
            "SR v4 power board, firmware 3 (USB)",
            "SRV4PowerBoard", ("sr.v4.power_board", "sr.v4", "sim_backends"),
            _simulator(
                "sr-power", "sr_power_fw3:SRPowerBoardFw3Simulator",
                "SR v4 power board, firmware 3 (USB control transfers)", "SIMPB", "usb",
            ),
        ),
        _kind(
            "sr-v4-motor-fw3", "sr.v4.motor_board:MotorBoard",
            "SR v4 motor board, firmware 3 (serial, 1 Mbaud)",
            "SRV4MotorBoard", ("sr.v4.motor_board", "sr.v4", "sim_backends"),
            _simulator(
                "sr-motor", "sr_motor_fw3:SRMotorBoardFw3Simulator",
                "SR v4 motor board, firmware 3 (1 Mbaud)", "SIMMB", "serial",
            ),
            # Its probe (a resync byte and a version query at 1 Mbaud) is quick, and
            # nothing sent at 115200 baud can reach it as a motor command first.
            identify_order=10,
        ),
        _kind(
            "sr-v4-servo-fw2", "sr.v4.servo_board:ServoBoard",
            "SR v4 servo board, firmware 2 (USB)",
            "SRV4ServoBoard", ("sr.v4.servo_board", "sr.v4", "sim_backends"),
            _simulator(
                "sr-servo", "sr_servo_fw2:SRServoBoardFw2Simulator",
                "SR v4 servo board, firmware 2 (USB control transfers)", "SIMSB", "usb",
            ),
        ),
        _kind(
            "sb-arduino-2019", "sb.arduino:SBArduinoBoard",
            "SourceBots Arduino, 2019 firmware (serial, 115200 baud)",
            "SBArduino", ("sb.arduino", "sb.arduino", "sim_backends"),
            _simulator(
                "sb-arduino", "sb_arduino_2019:SBArduinoSimulator",
                "SourceBots Arduino, 2019 firmware (115200 baud)", "SIMSBA", "serial",
            ),
            identify_order=50,
        ),
        _kind(
            "sr-ruggeduino-fw1", "sr.v4.ruggeduino:Ruggeduino",
            "SR Ruggeduino, firmware 1 (serial, 115200 baud)",
            "SRV4Ruggeduino", ("sr.v4.ruggeduino", "sr.v4", "sim_backends"),
            _simulator(
                "sr-ruggeduino", "sr_ruggeduino_fw1:SRRuggeduinoSimulator",
                "SR Ruggeduino, firmware 1 (115200 baud)", "SIMRD", "serial",
            ),
            identify_order=60,
        ),
        _kind(
            "sr-v4-power-fw4", "sr.v4.power_board_fw4:PowerBoardFw4",
            "SR v4 power board, firmware 4.4 (CDC serial)",
            "SRV4PowerBoardFw4", ("sr.v4.power_board_fw4", "sr.v4", "sim_backends_2023"),
            _simulator(
                "sr-power-fw4", "sr_power_fw4:SRPowerBoardFw4Simulator",
                "SR v4 power board, firmware 4.4 (CDC serial)", "SIMPB", "serial",
            ),
            identify_order=20,
        ),
        _kind(
            "sr-v4-motor-fw4", "sr.v4.motor_board_fw4:MotorBoardFw4",
            "SR v4 motor board, firmware 4.4 / 4.5 (serial, 115200 baud)",
            "SRV4MotorBoardFw4", ("sr.v4.motor_board_fw4", "sr.v4", "sim_backends_2023"),
            _simulator(
                "sr-motor-fw4", "sr_motor_fw4:SRMotorBoardFw4Simulator",
                "SR v4 motor board, firmware 4.4 (115200 baud)", "SIMMB", "serial",
            ),
            _simulator(
                "sb-motor-fw4", "sr_motor_fw4:SRMotorBoardFw4Simulator",
                "SR v4 motor board, SourceBots firmware 4.5 (115200 baud)", "SIMMB", "serial",
                version="4.5.0",
            ),
            # Its probe (a NUL, then *IDN? at 115200 baud) is harmless to a firmware 3
            # board, which takes the NUL as a resync and ignores the rest.
            identify_order=12,
        ),
        _kind(
            "sr-v4-servo-fw4", "sr.v4.servo_board_fw4:ServoBoardFw4",
            "SR v4 servo board, firmware 4.3 (CDC serial, 12 servos)",
            "SRV4ServoBoardFw4", ("sr.v4.servo_board_fw4", "sr.v4", "sim_backends_2023"),
            _simulator(
                "sr-servo-fw4", "sr_servo_fw4:SRServoBoardFw4Simulator",
                "SR v4 servo board, firmware 4.3 (CDC serial, 12 servos)", "SIMSB", "serial",
            ),
            identify_order=30,
        ),
        _kind(
            "sb-servo-fw4", "sb.servo_board:SBServoBoard",
            "SR v4 servo board, SourceBots firmware 4.4 (CDC serial, 8 servos)",
            "SBServoBoard", ("sr.v4.servo_board_fw4", "sr.v4", "sim_backends_2023"),
            _simulator(
                "sb-servo-fw4", "sr_servo_fw4:SBServoBoardFw4Simulator",
                "SR v4 servo board, SourceBots firmware 4.4 (8 servos)", "SIMSB", "serial",
            ),
            identify_order=31,
        ),
        _kind(
            "sr-arduino-fw2", "sr.v4.arduino:SRArduinoBoard",
            "SR Arduino, firmware 2 (serial, 115200 baud)",
            "SRArduino", ("sr.v4.arduino", "sr.v4", "sim_backends_2023"),
            _simulator(
                "sr-arduino-fw2", "sr_ruggeduino_fw1:SRRuggeduinoSimulator",
                "SR Arduino, firmware 2 (115200 baud)", "SIMSRA", "serial",
                firmware_version=2,
            ),
            identify_order=55,
        ),
        _kind(
            "sb-arduino-2024", "sb.arduino_2024:SBArduino2024Board",
            "SourceBots Arduino, sb2024 firmware 2.0 (serial, 115200 baud)",
            "SBArduino2024", ("sb.arduino_2024", "sb.arduino_2024", "sim_backends_2023"),
            _simulator(
                "sb-arduino-2024", "sb_arduino_2024:SBArduino2024Simulator",
                "SourceBots Arduino, sb2024 firmware 2.0 (115200 baud)", "SIMSBA", "serial",
            ),
            # First of the Arduinos: every other Arduino firmware answers its probe
            # (``*IDN?`` and a line end) at once, with a boot banner, an error or an empty
            # line per byte, while this silent line-based firmware would leave their
            # probes (waiting for a banner; ``v`` with no line end) to time out.
            identify_order=45,
        ),
        _kind(
            "sr-kch", "sr.kch:KCHBoard",
            "SR KCH, the Raspberry Pi HAT (GPIO: user and start LEDs)",
            "KCH", ("sr.kch", "sr.kch", "kch"),
            _simulator(
                "kch", "kch:KCHSimulator", "SR KCH (mock GPIO pins)", "SIMKCH", "other",
                serial_keyword="serial_number",
            ),
        ),
        BoardKind(
            name="camera",
            board="j5aio.boards.camera:CameraBoard",
            description="a webcam finding AprilTag markers (the optional extra j5aio[vision])",
            hardware="j5aio.backends.camera.opencv:OpenCVCameraBackend",
            console="j5aio.backends.console.camera:CameraConsoleBackend",
            # Every simulated kit has the robot's camera in its arena (kit.camera).
            simulated="j5aio.simulator._camera_backend:SimulatedCameraBackend",
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

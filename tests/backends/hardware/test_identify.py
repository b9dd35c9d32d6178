"""attach(port): whichever supported serial board answers on a port, identified."""

from __future__ import annotations

import sys
import time
from collections.abc import AsyncIterator, Callable, Iterator

import anyio
import pytest

from j5aio.backends.hardware import attach, registry
from j5aio.backends.hardware.identify import discover_serial_boards, serial_backends
from j5aio.backends.hardware.options import DiscoveryOptions
from j5aio.backends.hardware.sb.arduino import SBArduinoHardwareBackend
from j5aio.backends.hardware.serial_backend import SerialHardwareBackend
from j5aio.backends.hardware.sr.v4.motor_board import SRV4MotorBoardHardwareBackend
from j5aio.backends.hardware.sr.v4.ruggeduino import SRV4RuggeduinoHardwareBackend
from j5aio.backends.hardware.transports.discovery import PortInfo
from j5aio.backends.hardware.transports.memory import SimulatorStream
from j5aio.backends.hardware.transports.stream import ByteStream
from j5aio.boards.board import Board
from j5aio.boards.sb import SBArduinoBoard
from j5aio.boards.sr.v4 import MotorBoard, Ruggeduino
from j5aio.errors import CommunicationError, UnsupportedFirmwareError
from j5aio.simulator import (
    SBArduino2024Simulator,
    SBArduinoFirmware,
    SBArduinoSimulator,
    SerialBoardSimulator,
    SRMotorBoardFw3Simulator,
    SRRuggeduinoSimulator,
)
from j5aio.simulator.serve import PtyServer, serve_on_pty

pytestmark = pytest.mark.skipif(
    sys.platform == "win32", reason="pseudo-terminals exist on POSIX systems only"
)


@pytest.fixture(autouse=True)
async def _close_boards() -> AsyncIterator[None]:
    yield
    for board in list(Board.BOARDS):
        await board.close()
    registry.clear()


@pytest.fixture
def serve() -> Iterator[list[PtyServer]]:
    servers: list[PtyServer] = []
    yield servers
    for server in servers:
        server.close()


def served(servers: list[PtyServer], simulator: SerialBoardSimulator) -> str:
    server = serve_on_pty(simulator, time_scale=0)
    servers.append(server)
    return server.path


async def eventually(condition: Callable[[], bool]) -> None:
    """Wait (up to 5 s) for the simulator's thread to have done what ``condition`` checks."""
    with anyio.fail_after(5):
        while not condition():  # noqa: ASYNC110 - another thread changes it
            await anyio.sleep(0.01)


def test_serial_backends_come_in_identification_order() -> None:
    backends = serial_backends()
    order: list[type[SerialHardwareBackend]] = [
        SRV4MotorBoardHardwareBackend, SBArduinoHardwareBackend, SRV4RuggeduinoHardwareBackend,
    ]
    assert [backend for backend in backends if backend in order] == order


async def test_a_motor_board_is_identified_set_up_and_braked(serve: list[PtyServer]) -> None:
    simulator = SRMotorBoardFw3Simulator("MB1")
    board = await attach(served(serve, simulator), time_scale=0.3)
    assert isinstance(board, MotorBoard)
    assert board.firmware_version == "3"
    await eventually(lambda: [m.mode.value for m in simulator.motors] == ["brake", "brake"])
    await board.motors[0].set_power(0.5)
    await eventually(lambda: simulator.motors[0].mode.value == "forward")


@pytest.mark.parametrize("firmware", list(SBArduinoFirmware))
async def test_both_sb_arduino_firmwares_are_identified(
    serve: list[PtyServer], firmware: SBArduinoFirmware
) -> None:
    simulator = SBArduinoSimulator("SB1", firmware_version=firmware)
    simulator.set_analogue(14, volts=2.5)
    path = served(serve, simulator)
    board = await attach(path, time_scale=0.3)
    assert isinstance(board, SBArduinoBoard)
    assert board.firmware_version == firmware.value
    assert board.serial_number == path
    assert await board.pins[14].analogue_read() == pytest.approx(2.5, abs=0.01)


async def test_a_ruggeduino_is_identified_after_the_others_said_no(
    serve: list[PtyServer],
) -> None:
    simulator = SRRuggeduinoSimulator("RD1")
    path = served(serve, simulator)
    started = time.monotonic()
    board = await attach(path, time_scale=0.3)
    assert isinstance(board, Ruggeduino)
    assert board.firmware_version == "1"
    assert time.monotonic() - started < 10  # liveness only
    # Attaching again gives back the board that holds the port.
    assert await attach(path, time_scale=0.3) is board


class Answering(SerialBoardSimulator):
    """A board that answers every ``v`` with a fixed line, and nothing else."""

    baudrate = 115200
    boot_delay = 0.0
    resets_on_open = True
    powered_by_usb = True

    def __init__(self, answer: bytes) -> None:
        super().__init__("X", usb_vid=0x2341, usb_pid=0x0043, manufacturer=None, product=None)
        self._answer = answer

    def _boot(self) -> bytes:
        return b""

    def _process(self, data: bytes) -> bytes:
        return self._answer * data.count(b"v")


async def test_unsupported_firmware_is_reported_as_such(serve: list[PtyServer]) -> None:
    with pytest.raises(UnsupportedFirmwareError, match=r"(Ruggeduino|SR Arduino).*'7'"):
        await attach(served(serve, Answering(b"SRduino:7\n")), time_scale=0.3)


async def test_a_port_nothing_recognises_lists_what_was_tried() -> None:
    async def opener(port: str, baudrate: int) -> ByteStream:
        return SimulatorStream(Answering(b""), name=port, time_scale=0)

    with pytest.raises(CommunicationError, match=r"no supported board answered on silent0.*"
                       r"tried: .*Motor Board \(SRV4MotorBoardHardwareBackend\)"):
        await attach("silent0", time_scale=0.02, opener=opener)


async def test_discovery_asks_a_shared_port_once_and_finds_each_board_once() -> None:
    simulators: dict[str, SerialBoardSimulator] = {
        "/dev/ttyACM0": SBArduinoSimulator("SBA"),
        "/dev/ttyACM1": SRRuggeduinoSimulator("RDA"),
        "/dev/ttyUSB0": SRMotorBoardFw3Simulator("MBA"),
    }
    opened: list[tuple[str, int]] = []

    def ports() -> list[PortInfo]:
        return [
            PortInfo(path, sim.usb_vid, sim.usb_pid, sim.serial_number, sim.manufacturer,
                     sim.product)
            for path, sim in simulators.items()
        ]

    async def opener(port: str, baudrate: int) -> ByteStream:
        opened.append((port, baudrate))
        return SimulatorStream(simulators[port], name=port, time_scale=0)

    boards = await discover_serial_boards(
        options=DiscoveryOptions(port_source=ports, opener=opener, time_scale=0.3)
    )
    kinds = {board.serial_number: type(board) for board in boards}
    assert kinds == {"SBA": SBArduinoBoard, "RDA": Ruggeduino, "MBA": MotorBoard}
    # The motor board's port is opened by its own kind only; the SB Arduino's by one
    # identification: the sb2024 kind's probe, then the 2019 kind's, which takes it.
    assert opened.count(("/dev/ttyUSB0", 1_000_000)) == 1
    assert [entry for entry in opened if entry[0] == "/dev/ttyACM0"] == [
        ("/dev/ttyACM0", 115200)
    ] * 2


async def test_each_arduino_kinds_discovery_identifies_shared_ports_once() -> None:
    simulators: dict[str, SerialBoardSimulator] = {
        "/dev/ttyACM0": SBArduinoSimulator("SBA"),
        "/dev/ttyACM1": SRRuggeduinoSimulator("RDA"),
    }
    opened: list[tuple[str, int]] = []

    def ports() -> list[PortInfo]:
        return [
            PortInfo(path, sim.usb_vid, sim.usb_pid, sim.serial_number) for path, sim in
            simulators.items()
        ]

    async def opener(port: str, baudrate: int) -> ByteStream:
        opened.append((port, baudrate))
        return SimulatorStream(simulators[port], name=port, time_scale=0)

    options = DiscoveryOptions(port_source=ports, opener=opener, time_scale=0.3)
    arduinos = await SBArduinoHardwareBackend.discover(options=options)
    assert [board.serial_number for board in arduinos] == ["SBA"]
    # The Ruggeduino was identified on the way, and is held: its own discovery gives it
    # back without opening its port again.
    opened_before = list(opened)
    ruggeduinos = await SRV4RuggeduinoHardwareBackend.discover(options=options)
    assert [board.serial_number for board in ruggeduinos] == ["RDA"]
    assert opened == opened_before
    assert opened.count(("/dev/ttyACM0", 115200)) == 2  # the sb2024 probe, then the 2019 kind
    for board in [*arduinos, *ruggeduinos]:
        await board.close()


async def test_without_shared_port_identification_each_kind_tries_its_matches() -> None:
    simulator = SRRuggeduinoSimulator("RDB")

    async def opener(port: str, baudrate: int) -> ByteStream:
        return SimulatorStream(simulator, name=port, time_scale=0)

    options = DiscoveryOptions(
        port_source=lambda: [PortInfo("/dev/ttyACM5", simulator.usb_vid, simulator.usb_pid, "RDB")],
        opener=opener,
        time_scale=0.3,
        identify_shared_ports=False,
    )
    boards = await SRV4RuggeduinoHardwareBackend.discover(options=options)
    assert [board.serial_number for board in boards] == ["RDB"]
    await boards[0].close()


TODAYS_BOARDS = [
    ("sr-power-fw4", "PowerBoardFw4", "4.4.2"),
    ("sr-motor-fw4", "MotorBoardFw4", "4.4.1"),
    ("sb-motor-fw4", "MotorBoardFw4", "4.5.0"),
    ("sr-servo-fw4", "ServoBoardFw4", "4.3"),
    ("sb-servo-fw4", "SBServoBoard", "4.4"),
    ("sr-arduino-fw2", "SRArduinoBoard", "2"),
    ("sb-arduino-2024", "SBArduino2024Board", "2.0"),
]


@pytest.mark.parametrize(("name", "board_class", "version"), TODAYS_BOARDS)
async def test_each_of_todays_boards_is_identified_with_the_version_it_reported(
    serve: list[PtyServer], name: str, board_class: str, version: str
) -> None:
    from j5aio.simulator import SERIAL_SIMULATORS

    simulator = SERIAL_SIMULATORS[name]("T1")
    path = served(serve, simulator)
    started = time.monotonic()
    board = await attach(path, time_scale=0.3)
    assert type(board).__name__ == board_class
    assert board.firmware_version == version
    assert time.monotonic() - started < 15  # liveness only


@pytest.mark.parametrize("name", ["sr-arduino-fw2", "sb-arduino-2024", "sb-arduino"])
async def test_an_attached_arduino_has_ultrasound_sensors_and_no_echo_is_none(
    serve: list[PtyServer], name: str
) -> None:
    from j5aio.simulator import SERIAL_SIMULATORS

    simulator = SERIAL_SIMULATORS[name]("U1")
    assert isinstance(
        simulator, SBArduinoSimulator | SRRuggeduinoSimulator | SBArduino2024Simulator
    )
    simulator.set_ultrasound_distance(4, 5, 0.5)
    board = await attach(served(serve, simulator), time_scale=0.3)
    sensor = board.ultrasound_sensors[4, 5]  # type: ignore[attr-defined]
    assert await sensor.distance() == pytest.approx(0.5, abs=0.002)
    assert await board.ultrasound_sensors[6, 7].distance() is None  # type: ignore[attr-defined]


async def test_the_sb2024_arduino_is_identified_quickly_among_the_arduinos(
    serve: list[PtyServer],
) -> None:
    # Asked first, it does not wait out the probes of the other Arduino firmwares.
    backends = [backend.__name__ for backend in serial_backends()]
    arduinos = [name for name in backends if "Arduino" in name or "Ruggeduino" in name]
    assert arduinos[0] == "SBArduino2024HardwareBackend"
    started = time.monotonic()
    board = await attach(served(serve, SBArduino2024Simulator("Q1")), time_scale=1.0)
    assert board.firmware_version == "2.0"
    assert time.monotonic() - started < 10  # liveness only (it took 43 s when asked last)

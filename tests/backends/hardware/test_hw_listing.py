from types import SimpleNamespace
from typing import Any

import pytest

from j5aio.backends.hardware import listing, registry
from j5aio.backends.hardware.listing import FoundBoard, find_boards, format_boards
from j5aio.backends.hardware.options import DiscoveryOptions
from j5aio.backends.hardware.transports.memory import SimulatorStream
from j5aio.simulator.base import SerialBoardSimulator
from j5aio.simulator.sb_arduino_2019 import SBArduinoSimulator
from j5aio.simulator.sr_motor_fw3 import SRMotorBoardFw3Simulator
from j5aio.simulator.sr_power_fw3 import SRPowerBoardFw3Simulator
from j5aio.simulator.sr_ruggeduino_fw1 import SRRuggeduinoSimulator
from j5aio.simulator.sr_servo_fw2 import SRServoBoardFw2Simulator


def port_of(device: str, sim: SerialBoardSimulator) -> SimpleNamespace:
    return SimpleNamespace(
        device=device,
        vid=sim.usb_vid,
        pid=sim.usb_pid,
        serial_number=sim.serial_number,
        manufacturer=sim.manufacturer,
        product=sim.product,
        description="",
    )


def kit_options(
    serial: dict[str, SerialBoardSimulator], usb: list[Any]
) -> DiscoveryOptions:
    """Discovery options that find ``serial`` (by port) and ``usb`` simulators."""

    async def opener(port: str, baudrate: int) -> SimulatorStream:
        return SimulatorStream(serial[port], time_scale=0)

    def finder(*, find_all: bool, idVendor: int, idProduct: int) -> list[Any]:  # noqa: N803
        return [d for d in usb if (d.idVendor, d.idProduct) == (idVendor, idProduct)]

    return DiscoveryOptions(
        port_source=lambda: [port_of(device, sim) for device, sim in serial.items()],
        usb_finder=finder,
        opener=opener,
        time_scale=0.01,
    )


async def test_find_boards_lists_every_kind_and_closes_them() -> None:
    serial: dict[str, SerialBoardSimulator] = {
        "/dev/ttyUSB0": SRMotorBoardFw3Simulator("SRMOTOR"),
        "/dev/ttyACM0": SBArduinoSimulator("SBDUINO"),
        "/dev/ttyACM1": SRRuggeduinoSimulator("RUGGED"),
    }
    usb = [SRPowerBoardFw3Simulator("SRPOWER"), SRServoBoardFw2Simulator("SRSERVO")]

    options = kit_options(serial, usb)
    found = await find_boards(options=options)
    assert {(b.board_type, b.serial_number, b.firmware_version) for b in found} == {
        ("Student Robotics v4 Power Board", "SRPOWER", "3"),
        ("Student Robotics v4 Servo Board", "SRSERVO", "2"),
        ("Student Robotics v4 Motor Board", "SRMOTOR", "3"),
        ("SourceBots Arduino", "SBDUINO", "2019.6.0"),
        ("Ruggeduino", "RUGGED", "1"),
    }
    ports = {b.serial_number: b.port for b in found}
    assert ports["SRMOTOR"] == "/dev/ttyUSB0"
    assert ports["RUGGED"] == "/dev/ttyACM1"
    assert registry.held() == frozenset()


async def test_find_boards_leaves_a_board_held_by_a_robot_open() -> None:
    sim = SRMotorBoardFw3Simulator("SRMOTOR")

    async def opener(port: str, baudrate: int) -> SimulatorStream:
        return SimulatorStream(sim, time_scale=0)

    options = DiscoveryOptions(
        port_source=lambda: [port_of("/dev/ttyUSB0", sim)],
        usb_finder=lambda **_: [],
        opener=opener,
    )
    from j5aio.backends.hardware.sr.v4 import SRV4MotorBoardHardwareBackend

    board = await SRV4MotorBoardHardwareBackend.attach("/dev/ttyUSB0", opener=opener)
    found = await find_boards(options=options)
    assert [b.serial_number for b in found] == ["/dev/ttyUSB0"]
    assert registry.holder("/dev/ttyUSB0") is board
    await board.close()


def test_format_boards() -> None:
    assert "No boards found" in format_boards([])
    text = format_boards(
        [
            FoundBoard("Student Robotics v4 Motor Board", "SRM1", "3", "/dev/ttyUSB0"),
            FoundBoard("Ruggeduino", "R1", None, "/dev/ttyACM0"),
        ]
    )
    lines = text.splitlines()
    assert lines[0].split() == ["Board", "Serial", "number", "Firmware", "Port"]
    assert "SRM1" in lines[1] and "/dev/ttyUSB0" in lines[1]
    assert lines[2].startswith("Ruggeduino") and " - " in lines[2]
    assert lines[-1] == "2 boards found."
    assert format_boards([FoundBoard("X", "1", "1", "p")]).endswith("1 board found.")


async def test_find_boards_defaults_to_a_short_boot_wait_and_skips_failures(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    seen: list[DiscoveryOptions | None] = []

    class Recorder:
        @classmethod
        async def discover(cls, *, options: DiscoveryOptions | None = None) -> list[Any]:
            seen.append(options)
            return []

    monkeypatch.setattr(listing, "HARDWARE_BACKENDS", (Recorder,))
    assert await find_boards() == []
    assert seen == [DiscoveryOptions(time_scale=listing.LISTING_TIME_SCALE, skip_failures=True)]


async def test_find_boards_still_lists_serial_boards_when_usb_cannot_be_searched() -> None:
    from j5aio.errors import CommunicationError

    sim = SRMotorBoardFw3Simulator("SRMOTOR")

    async def opener(port: str, baudrate: int) -> SimulatorStream:
        return SimulatorStream(sim, time_scale=0)

    def no_libusb(**_: Any) -> list[Any]:
        raise CommunicationError("pyusb found no libusb backend")

    options = DiscoveryOptions(
        port_source=lambda: [port_of("/dev/ttyUSB0", sim)],
        usb_finder=no_libusb,
        opener=opener,
    )
    problems: list[str] = []
    found = await find_boards(options=options, problems=problems)
    assert [b.serial_number for b in found] == ["SRMOTOR"]
    assert problems == [
        "Student Robotics v4 Power Board: pyusb found no libusb backend",
        "Student Robotics v4 Servo Board: pyusb found no libusb backend",
    ]
    with pytest.raises(CommunicationError, match="no libusb"):
        await find_boards(options=options)


async def test_find_boards_lists_every_generation_of_both_kits() -> None:
    from j5aio.simulator import SERIAL_SIMULATORS

    names = {
        "/dev/ttyUSB0": "sr-motor",
        "/dev/ttyUSB1": "sr-motor-fw4",
        "/dev/ttyUSB2": "sb-motor-fw4",
        "/dev/ttyACM0": "sb-arduino",
        "/dev/ttyACM1": "sr-ruggeduino",
        "/dev/ttyACM2": "sr-arduino-fw2",
        "/dev/ttyACM3": "sb-arduino-2024",
        "/dev/ttyACM4": "sr-power-fw4",
        "/dev/ttyACM5": "sr-servo-fw4",
        "/dev/ttyACM6": "sb-servo-fw4",
    }
    serial: dict[str, SerialBoardSimulator] = {
        device: SERIAL_SIMULATORS[name](f"S{index}") for index, (device, name)
        in enumerate(names.items())
    }
    usb = [SRPowerBoardFw3Simulator("SRPOWER"), SRServoBoardFw2Simulator("SRSERVO")]

    options = kit_options(serial, usb)
    found = await find_boards(options=options)
    listed = {(b.serial_number, b.board_type, b.firmware_version) for b in found}
    assert listed == {
        ("SRPOWER", "Student Robotics v4 Power Board", "3"),
        ("SRSERVO", "Student Robotics v4 Servo Board", "2"),
        ("S0", "Student Robotics v4 Motor Board", "3"),
        ("S1", "Student Robotics v4 Motor Board (firmware 4)", "4.4.1"),
        ("S2", "Student Robotics v4 Motor Board (firmware 4)", "4.5.0"),
        ("S3", "SourceBots Arduino", "2019.6.0"),
        ("S4", "Ruggeduino", "1"),
        ("S5", "SR Arduino", "2"),
        ("S6", "SourceBots Arduino (sb2024)", "2.0"),
        ("S7", "Student Robotics v4 Power Board (firmware 4)", "4.4.2"),
        ("S8", "Student Robotics v4 Servo Board (firmware 4.3)", "4.3"),
        ("S9", "SourceBots Servo Board (firmware 4.4)", "4.4"),
    }
    assert {b.serial_number: b.port for b in found}["S6"] == "/dev/ttyACM3"
    assert len(found) == len(listed)  # each board once
    assert registry.held() == frozenset()
    # What `python -m j5aio list` prints names every generation.
    text = format_boards(found)
    for _, board_type, version in listed:
        assert board_type in text and str(version) in text

import logging
import threading
from types import SimpleNamespace
from typing import Any

import anyio
import pytest
import usb.core

from j5aio.backends.hardware import HARDWARE_ENVIRONMENT, registry
from j5aio.backends.hardware.options import DiscoveryOptions
from j5aio.backends.hardware.sb import SBArduinoHardwareBackend
from j5aio.backends.hardware.sr.v4 import (
    SRV4MotorBoardHardwareBackend,
    SRV4PowerBoardHardwareBackend,
    SRV4RuggeduinoHardwareBackend,
    SRV4ServoBoardHardwareBackend,
)
from j5aio.backends.hardware.transports.discovery import PortInfo
from j5aio.backends.hardware.transports.memory import SimulatorStream
from j5aio.backends.hardware.transports.stream import ByteStream
from j5aio.backends.hardware.usb_backend import USBHardwareBackend, device_key
from j5aio.boards.sb import SBArduinoBoard
from j5aio.boards.sr.v4 import MotorBoard, PowerBoard, Ruggeduino, ServoBoard
from j5aio.errors import (
    DeviceMissingSerialNumberError,
    UnsupportedFirmwareError,
    USBCommunicationError,
)
from j5aio.simulator.base import SerialBoardSimulator
from j5aio.simulator.sr_motor_fw3 import SRMotorBoardFw3Simulator
from j5aio.simulator.sr_power_fw3 import SRPowerBoardFw3Simulator
from j5aio.simulator.sr_servo_fw2 import SRServoBoardFw2Simulator
from j5aio.testing.transports import ScriptedStream
from tests.dataclass_twins import assert_like_generated


def motor_port(device: str, serial_number: str | None) -> SimpleNamespace:
    return SimpleNamespace(
        device=device,
        vid=0x0403,
        pid=0x6001,
        serial_number=serial_number,
        manufacturer="Student Robotics",
        product="MCV4B",
        description="MCV4B",
    )


class Bench:
    """Stand-in serial ports, each served by a simulator through a SimulatorStream."""

    def __init__(self, sims: dict[str, SerialBoardSimulator]) -> None:
        self.sims = sims
        self.opened: list[str] = []

    async def open(self, port: str, baudrate: int) -> SimulatorStream:
        self.opened.append(port)
        sim = self.sims[port]
        assert baudrate == sim.baudrate
        return SimulatorStream(sim, time_scale=0)


def test_environment_has_a_backend_for_every_board() -> None:
    assert HARDWARE_ENVIRONMENT.get_backend(PowerBoard) is SRV4PowerBoardHardwareBackend
    assert HARDWARE_ENVIRONMENT.get_backend(MotorBoard) is SRV4MotorBoardHardwareBackend
    assert HARDWARE_ENVIRONMENT.get_backend(ServoBoard) is SRV4ServoBoardHardwareBackend
    assert HARDWARE_ENVIRONMENT.get_backend(Ruggeduino) is SRV4RuggeduinoHardwareBackend
    assert HARDWARE_ENVIRONMENT.get_backend(SBArduinoBoard) is SBArduinoHardwareBackend
    import j5aio.backends.hardware as hardware

    with pytest.raises(AttributeError, match="NOPE"):
        hardware.NOPE  # noqa: B018


async def test_motor_boards_are_discovered_concurrently_and_rediscovered() -> None:
    bench = Bench(
        {"/dev/m1": SRMotorBoardFw3Simulator("M1"), "/dev/m2": SRMotorBoardFw3Simulator("M2")}
    )
    ports = [
        motor_port("/dev/m2", "M2"),
        motor_port("/dev/m1", "M1"),
        SimpleNamespace(**{**vars(motor_port("/dev/other", "O")), "product": "FT232R"}),
    ]
    options = DiscoveryOptions(port_source=lambda: ports, opener=bench.open)
    boards = await SRV4MotorBoardHardwareBackend.discover(options=options)
    assert [b.serial_number for b in boards] == ["M1", "M2"]
    again = await SRV4MotorBoardHardwareBackend.discover(options=options)
    assert again == boards
    assert sorted(bench.opened) == ["/dev/m1", "/dev/m2"]
    for board in boards:
        await board.close()


async def test_a_motor_board_without_serial_number_is_refused() -> None:
    options = DiscoveryOptions(port_source=lambda: [motor_port("/dev/m1", None)])
    with pytest.raises(DeviceMissingSerialNumberError, match="no USB serial number"):
        await SRV4MotorBoardHardwareBackend.discover(options=options)


async def test_a_failing_board_raises_or_is_skipped(caplog: pytest.LogCaptureFixture) -> None:
    good = SRMotorBoardFw3Simulator("M1")

    async def opener(port: str, baudrate: int) -> ByteStream:
        if port == "/dev/m1":
            return SimulatorStream(good, time_scale=0)
        return ScriptedStream([(b"\x00\x01", b"MCV4B:2\n")])

    ports = [motor_port("/dev/m1", "M1"), motor_port("/dev/m2", "M2")]
    # Only the firmware 3 backend: the scripted port knows nothing of the fw 4 probe.
    options = DiscoveryOptions(
        port_source=lambda: ports,
        opener=opener,
        identify_shared_ports=False,
    )
    with pytest.raises(UnsupportedFirmwareError, match="'2'"):
        await SRV4MotorBoardHardwareBackend.discover(options=options)
    held = registry.holder("/dev/m1")
    assert held is not None
    await held.close()
    skipping = DiscoveryOptions(
        port_source=lambda: ports,
        opener=opener,
        skip_failures=True,
        identify_shared_ports=False,
    )
    with caplog.at_level(logging.WARNING):
        boards = await SRV4MotorBoardHardwareBackend.discover(options=skipping)
    assert [b.serial_number for b in boards] == ["M1"]
    assert "/dev/m2" in caplog.text
    for board in boards:
        await board.close()


async def test_concurrent_attaches_share_one_board() -> None:
    sim = SRMotorBoardFw3Simulator("M1")
    bench = Bench({"/dev/m1": sim})
    results: list[object] = []

    async def attach() -> None:
        results.append(await SRV4MotorBoardHardwareBackend.attach("/dev/m1", opener=bench.open))

    async with anyio.create_task_group() as group:
        for _ in range(3):
            group.start_soon(attach)
    assert len(bench.opened) == 1
    assert results[0] is results[1] is results[2]
    await results[0].close()  # type: ignore[attr-defined]


def finder_for(*devices: Any) -> Any:
    def find(*, find_all: bool, idVendor: int, idProduct: int) -> list[Any]:  # noqa: N803
        assert find_all
        return [d for d in devices if (d.idVendor, d.idProduct) == (idVendor, idProduct)]

    return find


async def test_usb_boards_are_discovered_and_rediscovered() -> None:
    power = SRPowerBoardFw3Simulator("PB1")
    servo = SRServoBoardFw2Simulator("SB1")
    options = DiscoveryOptions(usb_finder=finder_for(power, servo))
    [power_board] = await SRV4PowerBoardHardwareBackend.discover(options=options)
    [servo_board] = await SRV4ServoBoardHardwareBackend.discover(options=options)
    assert power_board.serial_number == "PB1"
    assert servo_board.serial_number == "SB1"
    assert await SRV4PowerBoardHardwareBackend.discover(options=options) == [power_board]
    assert servo.init_requests == 1
    assert str(getattr(power_board.backend, "port", "")).startswith("usb:1bda:0010#")
    await power_board.close()
    await servo_board.close()


async def test_a_finder_that_answers_at_once_runs_in_the_loop_and_others_on_a_thread() -> None:
    power = SRPowerBoardFw3Simulator("PB1")
    threads: list[int] = []

    def find(**kwargs: Any) -> list[Any]:
        threads.append(threading.get_ident())
        return list(finder_for(power)(**kwargs))

    [board] = await SRV4PowerBoardHardwareBackend.discover(
        options=DiscoveryOptions(usb_finder=find)
    )
    find.answers_at_once = True  # type: ignore[attr-defined]  # as the simulated kit's does
    assert await SRV4PowerBoardHardwareBackend.discover(
        options=DiscoveryOptions(usb_finder=find)
    ) == [board]
    assert threads[0] != threading.get_ident()  # a bus scan blocks: a worker thread
    assert threads[1] == threading.get_ident()
    # A simulator answers at once too: its link starts no thread for the handshake.
    backend = board.backend
    assert isinstance(backend, USBHardwareBackend)
    assert not backend.link.thread.is_alive()
    await board.close()


async def test_usb_discovery_failures() -> None:
    missing = SRPowerBoardFw3Simulator(None)
    options = DiscoveryOptions(usb_finder=finder_for(missing))
    with pytest.raises(DeviceMissingSerialNumberError):
        await SRV4PowerBoardHardwareBackend.discover(options=options)
    skipping = DiscoveryOptions(usb_finder=finder_for(missing), skip_failures=True)
    assert await SRV4PowerBoardHardwareBackend.discover(options=skipping) == []

    def broken(**_: Any) -> Any:
        raise usb.core.USBError("Access denied", errno=13)

    with pytest.raises(USBCommunicationError, match="Access denied"):
        await SRV4PowerBoardHardwareBackend.discover(options=DiscoveryOptions(usb_finder=broken))


def test_device_key_uses_bus_and_address() -> None:
    device = SimpleNamespace(idVendor=0x1BDA, idProduct=0x0011, bus=1, address=7)
    assert device_key(device) == "usb:1bda:0011@1.7"


def test_time_scale_must_not_be_negative() -> None:
    with pytest.raises(ValueError, match="time_scale"):
        DiscoveryOptions(time_scale=-1)


async def test_usb_backends_cannot_attach_to_a_port() -> None:
    from j5aio.errors import NotSupportedByHardwareError

    with pytest.raises(NotSupportedByHardwareError, match="cannot attach"):
        await SRV4PowerBoardHardwareBackend.attach("/dev/ttyACM0")


def test_discovery_options_are_the_generated_dataclass() -> None:
    assert_like_generated(
        DiscoveryOptions,
        [
            ((), {}),
            ((list, None, None, 0.5, True, False), {}),
            ((), {"time_scale": 0, "skip_failures": True}),
        ],
    )
    for scale in (-1.0, float("nan")):
        with pytest.raises(ValueError, match=r"time_scale must be a number >= 0, not"):
            DiscoveryOptions(time_scale=scale)


def test_port_info_is_the_generated_dataclass() -> None:
    assert_like_generated(
        PortInfo,
        [
            (("/dev/ttyACM0",), {}),
            (("/dev/ttyUSB0", 0x0403, 0x6001, "SR0A", "FTDI", "MCV4B", "a motor board"), {}),
            (("COM3",), {"vid": 0x2341, "description": "Uno"}),
        ],
    )

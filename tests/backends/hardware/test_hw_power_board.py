import struct
from datetime import timedelta
from typing import Any

import pytest
import usb.core

from j5aio.backends.hardware.sr.v4 import SRV4PowerBoardHardwareBackend
from j5aio.boards.sr.v4 import PowerBoard, PowerOutputPosition
from j5aio.components.piezo import Note
from j5aio.errors import (
    BoardDisconnectionError,
    CommunicationError,
    DeviceMissingSerialNumberError,
    NotSupportedByHardwareError,
    UnsupportedFirmwareError,
    USBCommunicationError,
)
from j5aio.simulator.sr_power_fw3 import SRPowerBoardFw3Simulator

Backend = SRV4PowerBoardHardwareBackend


async def connect(sim: SRPowerBoardFw3Simulator) -> tuple[PowerBoard, Backend]:
    board = await Backend.from_usb_device(sim)
    assert isinstance(board, PowerBoard)
    await board.setup()
    backend = board.backend
    assert isinstance(backend, Backend)
    return board, backend


class StandIn:
    """A pyusb-shaped device that answers from a table and records what it is sent."""

    idVendor = 0x1BDA  # noqa: N815
    idProduct = 0x0010  # noqa: N815

    def __init__(self, version: int = 3, serial_number: str | None = "PB1") -> None:
        self.version = version
        self.serial_number = serial_number
        self.writes: list[tuple[int, int, bytes]] = []
        self.fail_with: usb.core.USBError | None = None

    def ctrl_transfer(
        self,
        request_type: int,
        request: int,
        value: int = 0,
        index: int = 0,
        data: Any = None,
        timeout: int | None = None,
    ) -> Any:
        assert request == 64
        if self.fail_with is not None:
            raise self.fail_with
        if request_type == 0x80:
            assert index == 9
            return struct.pack("<I", self.version)
        self.writes.append((index, value, bytes(data)))
        return len(data)


async def test_handshake_reads_version_only() -> None:
    device = StandIn()
    board = await Backend.from_usb_device(device)
    assert board.firmware_version == "3"
    assert board.serial_number == "PB1"
    assert device.writes == []
    await board.close()


async def test_unsupported_firmware() -> None:
    with pytest.raises(UnsupportedFirmwareError, match="'4'") as info:
        await Backend.from_usb_device(StandIn(version=4))
    assert info.value.supported == ("3",)


async def test_missing_serial_number() -> None:
    with pytest.raises(DeviceMissingSerialNumberError, match="no USB serial number"):
        await Backend.from_usb_device(StandIn(serial_number=None))


async def test_outputs_leds_and_cached_states() -> None:
    sim = SRPowerBoardFw3Simulator("PB1")
    board, backend = await connect(sim)
    assert await board.outputs[PowerOutputPosition.L1].get_is_enabled() is False
    await board.outputs[PowerOutputPosition.L1].set_is_enabled(True)
    assert sim.outputs == (False, False, False, True, False, False)
    assert await board.outputs[PowerOutputPosition.L1].get_is_enabled() is True
    await board.outputs.power_on()
    assert all(sim.outputs)
    await board.make_safe()
    assert not any(sim.outputs)
    await board.run_led.set_state(False)
    await board.error_led.set_state(True)
    assert (sim.run_led, sim.error_led) == (False, True)
    assert await backend.get_led_state(1) is True
    with pytest.raises(ValueError, match="LEDs 0"):
        await backend.set_led_state(2, True)
    with pytest.raises(ValueError, match="LEDs 0"):
        await backend.get_led_state(2)
    with pytest.raises(ValueError, match="outputs 0 to 5"):
        await backend.set_power_output_enabled(6, True)
    with pytest.raises(ValueError, match="outputs 0 to 5"):
        await backend.get_power_output_enabled(-1)
    await board.close()


async def test_readings() -> None:
    sim = SRPowerBoardFw3Simulator("PB1", battery_voltage=11.5, battery_current=2.25)
    board, backend = await connect(sim)
    sim.set_output_current(2, 1.5)
    assert await board.outputs[PowerOutputPosition.L0].get_current() == 1.5
    assert await board.battery_sensor.get_voltage() == 11.5
    reported_ma, _ = struct.unpack("<II", bytes(sim.ctrl_transfer(0x80, 64, 0, 7, 8)))
    assert await board.battery_sensor.get_current() == reported_ma / 1000
    assert await board.start_button.get_is_pressed() is False
    sim.press_start()
    assert await board.start_button.get_is_pressed() is True
    await backend.wait_until_button_pressed(0)
    with pytest.raises(ValueError, match="only button 0"):
        await backend.get_button_state(1)
    with pytest.raises(ValueError, match="only battery sensor 0"):
        await backend.get_battery_sensor_voltage(1)
    with pytest.raises(ValueError, match="only battery sensor 0"):
        await backend.get_battery_sensor_current(1)
    with pytest.raises(ValueError, match="outputs 0 to 5"):
        await backend.get_power_output_current(6)
    await board.close()


async def test_wait_until_button_pressed_polls(monkeypatch: pytest.MonkeyPatch) -> None:
    sim = SRPowerBoardFw3Simulator("PB1")
    _, backend = await connect(sim)
    monkeypatch.setattr(Backend, "BUTTON_POLL_INTERVAL", 0.001)
    reads = 0
    original = backend.get_button_state

    async def counting(identifier: int) -> bool:
        nonlocal reads
        reads += 1
        if reads == 3:
            sim.press_start()
        return await original(identifier)

    monkeypatch.setattr(backend, "get_button_state", counting)
    await backend.wait_until_button_pressed(0)
    assert reads == 3
    await backend.close()


async def test_piezo_queue_and_the_too_fast_error() -> None:
    sim = SRPowerBoardFw3Simulator("PB1")
    board, backend = await connect(sim)
    await board.piezo.buzz(0.25, Note.A6)
    assert sim.note_queue[-1].frequency == 1760
    assert sim.note_queue[-1].duration_ms == 250
    for _ in range(sim.NOTE_QUEUE_CAPACITY - len(sim.note_queue)):
        await backend.buzz(0, timedelta(milliseconds=10), 440)
    with pytest.raises(CommunicationError, match="buzz commands were sent too quickly") as info:
        await backend.buzz(0, timedelta(milliseconds=10), 440)
    assert isinstance(info.value, USBCommunicationError)
    assert info.value.errno == 32
    with pytest.raises(NotSupportedByHardwareError, match="65535 ms"):
        await backend.buzz(0, timedelta(seconds=70), 440)
    with pytest.raises(ValueError, match="only piezo 0"):
        await backend.buzz(1, timedelta(seconds=1), 440)
    await board.close()


async def test_an_unplugged_board_is_a_disconnection() -> None:
    sim = SRPowerBoardFw3Simulator("PB1")
    board, backend = await connect(sim)
    assert backend.link.board_name == board.name
    assert repr(backend).startswith("<SRV4PowerBoardHardwareBackend usb:1bda:0010#")
    sim.unplug()
    with pytest.raises(BoardDisconnectionError):
        await board.battery_sensor.get_voltage()
    with pytest.raises(BoardDisconnectionError):
        await board.run_led.set_state(True)
    await board.close()


async def test_usb_errors_are_usb_communication_errors() -> None:
    device = StandIn()
    board = await Backend.from_usb_device(device)
    device.fail_with = usb.core.USBError("Input/Output Error", errno=5)
    with pytest.raises(USBCommunicationError, match="Input/Output"):
        await board.backend.set_led_state(0, True)  # type: ignore[attr-defined]
    await board.close()


async def test_make_safe_now_switches_every_output_off_synchronously() -> None:
    sim = SRPowerBoardFw3Simulator("PB1")
    board, backend = await connect(sim)
    await board.outputs.power_on()
    assert all(sim.outputs)
    assert backend.make_safe_now(0.5) is True
    assert not any(sim.outputs)
    assert await board.outputs[PowerOutputPosition.H0].get_is_enabled() is False
    backend.close_now()
    assert backend.make_safe_now(0.5) is False
    await board.close()

class _Configuration:
    def __init__(self, interfaces: int) -> None:
        self.bNumInterfaces = interfaces


class _CdcPowerBoard:
    """A firmware 4 power board as pyusb sees it: the fw 3 IDs, two (CDC) interfaces."""

    idVendor = 0x1BDA  # noqa: N815 - pyusb's names
    idProduct = 0x0010  # noqa: N815
    serial_number = "SRFW4"

    def get_active_configuration(self) -> _Configuration:
        return _Configuration(2)

    def ctrl_transfer(self, *args: Any, **kwargs: Any) -> Any:
        raise AssertionError("a fw 4 board must not be sent fw 3 control transfers")


class _Unreadable(_CdcPowerBoard):
    def get_active_configuration(self) -> _Configuration:
        raise usb.core.USBError("Access denied")


async def test_discovery_leaves_a_firmware_4_board_to_its_serial_backend() -> None:
    from j5aio.backends.hardware.options import DiscoveryOptions

    fw3 = SRPowerBoardFw3Simulator("SRFW3")
    fw4 = _CdcPowerBoard()
    options = DiscoveryOptions(usb_finder=lambda **_: [fw4, fw3])
    boards = await SRV4PowerBoardHardwareBackend.discover(options=options)
    try:
        assert [board.serial_number for board in boards] == ["SRFW3"]
    finally:
        for board in boards:
            await board.close()
    assert SRV4PowerBoardHardwareBackend.drives_device(fw3)
    assert not SRV4PowerBoardHardwareBackend.drives_device(fw4)
    assert SRV4PowerBoardHardwareBackend.drives_device(_Unreadable())
    assert SRV4PowerBoardHardwareBackend.drives_device(object())  # type: ignore[arg-type]

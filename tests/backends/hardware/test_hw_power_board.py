import struct
from datetime import timedelta
from typing import Any

import anyio
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
from j5aio.simulator.usb_support import UsbStall

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


async def wait_until(condition: Any) -> None:
    """Let other tasks and threads run until ``condition()`` (a liveness bound only)."""
    with anyio.fail_after(30):
        while not condition():  # noqa: ASYNC110 - a thread changes it
            await anyio.sleep(0.001)


class CountingSimulator(SRPowerBoardFw3Simulator):
    """Counts the button reads (on the link's thread) and presses when ``ready()`` says."""

    def __init__(self, serial_number: str) -> None:
        super().__init__(serial_number)
        self.button_reads = 0
        self.pressed_at: int | None = None
        self.ready: Any = lambda: False
        self.fail_reads = False

    def _read(self, command: int, length: int) -> bytes:
        if command == 8:
            self.button_reads += 1
            if self.fail_reads:
                raise UsbStall()
            if self.pressed_at is None and self.ready():
                self.pressed_at = self.button_reads
                self.press_start()
        return super()._read(command, length)


async def test_wait_until_button_pressed_polls(monkeypatch: pytest.MonkeyPatch) -> None:
    sim = CountingSimulator("PB1")
    _, backend = await connect(sim)
    monkeypatch.setattr(Backend, "BUTTON_POLL_INTERVAL", 0.001)
    sim.ready = lambda: sim.button_reads == 3
    await backend.wait_until_button_pressed(0)
    assert sim.button_reads == 3
    with pytest.raises(ValueError, match="only button 0"):
        await backend.wait_until_button_pressed(1)
    await backend.close()


@pytest.mark.parametrize("waiters", [1, 4])
async def test_waiters_share_one_poll_stream(
    monkeypatch: pytest.MonkeyPatch, waiters: int
) -> None:
    sim = CountingSimulator("PB1")
    board, backend = await connect(sim)
    monkeypatch.setattr(Backend, "BUTTON_POLL_INTERVAL", 0.001)
    watch = backend._presses
    # Pressed only once every waiter waits, after at least three reads.
    sim.ready = lambda: watch.waiters == waiters and sim.button_reads >= 3
    done = 0

    async def wait() -> None:
        nonlocal done
        await board.start_button.wait_until_pressed()
        done += 1

    async with anyio.create_task_group() as group:
        for _ in range(waiters):
            group.start_soon(wait)
    assert done == waiters
    # One stream: it stopped at the read that saw the press. A stream per waiter would
    # each have needed a read of its own to see it.
    assert sim.button_reads == sim.pressed_at
    assert not watch.polling
    assert watch.waiters == 0
    await anyio.sleep(0.02)  # nobody waits: nothing reads the board any more
    assert sim.button_reads == sim.pressed_at
    await backend.close()


async def test_a_cancelled_waiter_leaves_the_others_polling(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    sim = CountingSimulator("PB1")
    board, backend = await connect(sim)
    monkeypatch.setattr(Backend, "BUTTON_POLL_INTERVAL", 0.001)
    watch = backend._presses
    sim.ready = lambda: watch.waiters == 2 and sim.button_reads >= 3
    done = 0

    async def wait() -> None:
        nonlocal done
        await board.start_button.wait_until_pressed()
        done += 1

    leader = anyio.CancelScope()

    async def lead_then_give_up() -> None:
        with leader:
            await board.start_button.wait_until_pressed()

    async with anyio.create_task_group() as group:
        group.start_soon(lead_then_give_up)
        await wait_until(lambda: watch.polling)  # the first waiter leads the stream
        group.start_soon(wait)
        group.start_soon(wait)
        await wait_until(lambda: watch.waiters == 3)
        leader.cancel()
    assert done == 2
    assert sim.pressed_at is not None
    assert not watch.polling
    await backend.close()


async def test_a_failing_board_fails_every_waiter(monkeypatch: pytest.MonkeyPatch) -> None:
    sim = CountingSimulator("PB1")
    board, backend = await connect(sim)
    monkeypatch.setattr(Backend, "BUTTON_POLL_INTERVAL", 0.001)
    watch = backend._presses
    failed: list[BaseException] = []

    async def wait() -> None:
        with pytest.raises(USBCommunicationError, match=r"Power Board.*wIndex 8") as info:
            await board.start_button.wait_until_pressed()
        failed.append(info.value)

    async with anyio.create_task_group() as group:
        for _ in range(3):
            group.start_soon(wait)
        await wait_until(lambda: watch.waiters == 3)
        sim.fail_reads = True
    assert len(failed) == 3
    assert not watch.polling
    # The board answers again: a new wait polls anew.
    sim.fail_reads = False
    sim.ready = lambda: True
    await board.start_button.wait_until_pressed()
    await backend.close()


async def test_closing_the_link_ends_the_wait(monkeypatch: pytest.MonkeyPatch) -> None:
    sim = CountingSimulator("PB1")
    board, backend = await connect(sim)
    monkeypatch.setattr(Backend, "BUTTON_POLL_INTERVAL", 0.001)

    async def close_when_polling() -> None:
        await wait_until(lambda: sim.button_reads > 0)
        backend.link.close_now()

    async with anyio.create_task_group() as group:
        group.start_soon(close_when_polling)
        with pytest.raises(BoardDisconnectionError, match="closed"):
            await board.start_button.wait_until_pressed()


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

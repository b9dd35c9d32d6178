from datetime import timedelta
from typing import Any

import anyio
import pytest

from j5aio.backends.hardware.options import DiscoveryOptions
from j5aio.backends.hardware.sr.v4 import SRV4PowerBoardFw4HardwareBackend
from j5aio.backends.hardware.sr.v4.text_protocol import NackError
from j5aio.backends.hardware.transports.discovery import PortInfo
from j5aio.backends.hardware.transports.memory import SimulatorStream
from j5aio.boards.sr.v4 import PowerBoardFw4, PowerBoardOutput, PowerOutputPosition
from j5aio.components.flashing_led import LEDMode
from j5aio.components.piezo import Note
from j5aio.errors import (
    BoardDisconnectionError,
    CommunicationError,
    CommunicationTimeoutError,
    NotSupportedByHardwareError,
    UnexpectedReplyError,
    UnsupportedFirmwareError,
)
from j5aio.simulator import SRPowerBoardFw4Simulator
from j5aio.testing.transports import FaultyStream, RecordingStream, ScriptedStream

Backend = SRV4PowerBoardFw4HardwareBackend
IDN = (b"*IDN?\n", b"Student Robotics:PBv4B:srABC:4.4.2\n")
HANDSHAKE = [IDN, (b"*RESET\n", b"ACK\n")]


async def connect(
    sim: SRPowerBoardFw4Simulator,
) -> tuple[PowerBoardFw4, SRV4PowerBoardFw4HardwareBackend, RecordingStream]:
    stream = RecordingStream(SimulatorStream(sim, time_scale=0))
    board = await Backend.from_stream(stream, port="sim-power", serial_number=sim.serial_number)
    assert isinstance(board, PowerBoardFw4)
    await board.setup()
    backend = board.backend
    assert isinstance(backend, Backend)
    stream.clear()
    return board, backend, stream


async def test_handshake_bytes() -> None:
    stream = ScriptedStream(HANDSHAKE)
    board = await Backend.from_stream(stream, port="scripted", serial_number="srABC")
    stream.assert_all_used()
    assert board.firmware_version == "4.4.2"
    backend = board.backend
    assert isinstance(backend, Backend)
    assert backend.asset_tag == "srABC"
    await board.close()
    assert stream.is_closed


@pytest.mark.parametrize("version", ["4.5", "4.3.9", "3"])
async def test_unsupported_firmware(version: str) -> None:
    stream = ScriptedStream([(b"*IDN?\n", f"Student Robotics:PBv4B:srA:{version}\n".encode())])
    with pytest.raises(UnsupportedFirmwareError) as info:
        await Backend.from_stream(stream, port="scripted", serial_number="srA")
    assert info.value.found == version
    assert "4.4" in info.value.supported
    assert stream.is_closed


async def test_another_board_on_the_port() -> None:
    stream = ScriptedStream([(b"*IDN?\n", b"Student Robotics:MCv4B:srA:4.4\n")])
    with pytest.raises(UnexpectedReplyError, match="PBv4B"):
        await Backend.from_stream(stream, port="scripted", serial_number="srA")


async def test_outputs_and_the_brain() -> None:
    sim = SRPowerBoardFw4Simulator("srABC")
    board, _, stream = await connect(sim)
    await board.outputs[PowerBoardOutput.H0].set_is_enabled(True)
    assert stream.sent == b"OUT:0:SET:1\n"
    assert sim.outputs[0]
    assert board.outputs[PowerOutputPosition.H0] is board.outputs[PowerBoardOutput.H0]
    assert board.outputs[6] is board.outputs[PowerBoardOutput.FIVE_VOLT]
    assert len(board.outputs) == 7
    stream.clear()
    with pytest.raises(NotSupportedByHardwareError, match="L2"):
        await board.outputs[PowerBoardOutput.L2].set_is_enabled(False)
    assert stream.sent == b""
    assert await board.outputs[PowerBoardOutput.L2].get_is_enabled() is True
    await board.outputs.power_on()
    assert sim.outputs == (True,) * 7
    await board.outputs.power_off()
    assert sim.outputs == (False, False, False, False, True, False, False)
    sim.set_output_current(6, 1.25)
    await board.outputs[6].set_is_enabled(True)
    assert await board.outputs[6].get_current() == 1.25
    await board.close()


async def test_overcurrent_status_and_reset() -> None:
    sim = SRPowerBoardFw4Simulator("srABC")
    board, _, stream = await connect(sim)
    output = board.outputs[PowerBoardOutput.L1]
    await output.set_is_enabled(True)
    sim.trip_output(3)
    assert await output.get_is_overcurrent() is True  # type: ignore[attr-defined]
    assert await board.outputs[0].get_is_overcurrent() is False  # type: ignore[attr-defined]
    await output.set_is_enabled(True)  # ACKed, stays off
    assert await output.get_is_enabled() is False
    sim.temperature = 52
    sim.regulator_voltage = 4.95
    assert await board.temperature_sensor.get_temperature() == 52.0
    assert await board.fan.get_is_running() is True
    assert await board.regulator_sensor.get_voltage() == 4.95
    await board.run_led.set_mode(LEDMode.FLASH)
    stream.clear()
    await board.make_safe()
    assert stream.sent == b"*RESET\n"
    assert sim.overcurrent_latches == (False,) * 7
    assert sim.led_modes == ("0", "0")
    await board.close()


async def test_leds() -> None:
    sim = SRPowerBoardFw4Simulator("srABC")
    board, backend, stream = await connect(sim)
    await board.error_led.set_mode(LEDMode.FLASH)
    assert stream.sent == b"LED:ERR:SET:F\n"
    assert await board.error_led.get_mode() is LEDMode.FLASH
    assert await board.error_led.get_state() is True
    await board.run_led.set_state(True)
    assert sim.led_modes == ("1", "F")
    await board.error_led.set_state(False)
    assert await board.error_led.get_mode() is LEDMode.OFF
    with pytest.raises(TypeError, match="LEDMode"):
        await board.run_led.set_mode("F")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="LEDs 0"):
        await backend.set_led_mode(2, LEDMode.ON)
    await board.close()


async def test_buzzer_replaces_the_note() -> None:
    sim = SRPowerBoardFw4Simulator("srABC")
    board, backend, stream = await connect(sim)
    await board.piezo.buzz(1.0, Note.A6)
    await board.piezo.buzz(0.1, 440)
    assert stream.sent == b"NOTE:1760:1000\nNOTE:440:100\n"
    assert sim.playing is not None and sim.playing.frequency == 440
    stream.clear()
    with pytest.raises(NotSupportedByHardwareError, match="8 to 10000"):
        await board.piezo.buzz(0.5, 20_000)
    with pytest.raises(ValueError, match="only piezo 0"):
        await backend.buzz(1, timedelta(seconds=1), 440)
    assert stream.sent == b""
    await board.close()


async def test_latched_start_button() -> None:
    sim = SRPowerBoardFw4Simulator("srABC")
    board, _, stream = await connect(sim)
    sim.click_start(external=True)
    assert await board.start_button.get_is_pressed() is True
    assert await board.start_button.get_is_pressed() is False
    sim.click_start()  # before the wait: does not count
    with anyio.move_on_after(0.2) as scope:
        await board.start_button.wait_until_pressed()
    assert scope.cancelled_caught

    async def press_later() -> None:
        await anyio.sleep(0.1)
        sim.click_start()

    async with anyio.create_task_group() as group:
        group.start_soon(press_later)
        await board.wait_for_start_flash(timeout=5)
    assert sim.led_modes[0] == "1"
    assert b"LED:RUN:SET:F\n" in stream.sent
    await board.close()


async def test_battery() -> None:
    sim = SRPowerBoardFw4Simulator("srABC")
    board, backend, _ = await connect(sim)
    sim.battery_voltage = 11.9
    sim.battery_current = -0.5
    assert await board.battery_sensor.get_voltage() == 11.9
    assert await board.battery_sensor.get_current() == -0.5
    with pytest.raises(ValueError, match="only battery sensor 0"):
        await backend.get_battery_sensor_voltage(1)
    for call in (backend.get_temperature, backend.get_fan_running,
                 backend.get_voltage_sensor_voltage):
        with pytest.raises(ValueError, match="only"):
            await call(1)
    await board.close()


async def test_nack_and_malformed_replies_are_communication_errors() -> None:
    stream = ScriptedStream([*HANDSHAKE, (b"OUT:0:SET:1\n", b"NACK:Invalid output number\n"),
                             (b"OUT:0:GET?\n", b"yes\n"), (b"*STATUS?\n", b"0,0:30\n")])
    board = await Backend.from_stream(stream, port="scripted", serial_number="srABC")
    assert isinstance(board, PowerBoardFw4)
    with pytest.raises(NackError) as nack:
        await board.outputs[0].set_is_enabled(True)
    assert "OUT:0:SET:1" in str(nack.value) and board.name in str(nack.value)
    with pytest.raises(UnexpectedReplyError, match="yes"):
        await board.outputs[0].get_is_enabled()
    with pytest.raises(CommunicationError, match=r"\*STATUS\?"):
        await board.fan.get_is_running()
    await board.close()


async def test_discovery_by_usb_id() -> None:
    sim = SRPowerBoardFw4Simulator("srPB1")
    ports = [
        PortInfo("/dev/ttyACM0", 0x1BDA, 0x0010, "srPB1", "Student Robotics", "Power Board v4"),
        PortInfo("/dev/ttyACM1", 0x1BDA, 0x0011, "other", None, None),
    ]

    async def opener(port: str, baudrate: int) -> SimulatorStream:
        assert port == "/dev/ttyACM0"
        return SimulatorStream(sim, time_scale=0)

    boards = await Backend.discover(
        options=DiscoveryOptions(port_source=lambda: ports, opener=opener),
    )
    assert [board.serial_number for board in boards] == ["srPB1"]
    await boards[0].close()


def test_board_needs_a_backend_that_can_reset() -> None:
    with pytest.raises(TypeError, match="needs a backend that implements"):
        PowerBoardFw4("x", object())  # type: ignore[arg-type]


async def test_a_lost_or_corrupt_reply_is_an_error_and_the_next_call_works() -> None:
    sim = SRPowerBoardFw4Simulator("srABC")
    stream = FaultyStream(SimulatorStream(sim, time_scale=0))
    board = await Backend.from_stream(stream, port="faulty", serial_number="srABC")
    assert isinstance(board, PowerBoardFw4)
    stream.drop_next_reply()
    with pytest.raises(CommunicationTimeoutError, match="OUT:0:GET"):
        await board.outputs[0].get_is_enabled()
    stream.corrupt_next_reply()
    with pytest.raises(CommunicationError):
        await board.outputs[0].get_is_enabled()
    await board.outputs[0].set_is_enabled(True)
    assert await board.outputs[0].get_is_enabled() is True
    sim.unplug()
    with pytest.raises(BoardDisconnectionError):
        await board.outputs[0].get_is_enabled()
    await board.close()


async def test_make_safe_now_resets_the_board_synchronously() -> None:
    sim = SRPowerBoardFw4Simulator("srABC")
    board, backend, stream = await connect(sim)
    await board.outputs.power_on()
    await board.run_led.set_mode(LEDMode.FLASH)
    stream.clear()
    assert backend.make_safe_now(0.5) is True
    assert stream.sent == b"\n*RESET\n"
    assert sim.outputs == (False, False, False, False, True, False, False)
    assert sim.led_modes == ("0", "0")
    # The unanswered replies are drained; the next exchange gets its own reply.
    assert await board.outputs[PowerBoardOutput.H0].get_is_enabled() is False
    backend.close_now()
    assert backend.make_safe_now(0.5) is False
    await board.close()


async def test_a_note_is_not_sent_again_after_a_reconnection(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    board, backend, _ = await connect(SRPowerBoardFw4Simulator("srABC"))
    seen: list[bool] = []

    async def vanished(*args: object, **kwargs: object) -> None:
        raise BoardDisconnectionError("the port has gone")

    async def retry_after(
        error: BoardDisconnectionError, call: object, *, idempotent: bool
    ) -> None:
        seen.append(idempotent)  # whether the command would be sent again
        raise error

    monkeypatch.setattr(backend.link, "command", vanished)
    monkeypatch.setattr(backend, "_retry_after", retry_after)
    with pytest.raises(BoardDisconnectionError):
        await board.piezo.buzz(0.1, Note.A6)
    with pytest.raises(BoardDisconnectionError):
        await board.outputs[PowerBoardOutput.H0].set_is_enabled(True)
    assert seen == [False, True]
    monkeypatch.undo()
    await board.close()


async def test_the_handshake_tolerates_leftovers_ahead_of_its_line() -> None:
    # Another probe left "v" on the line: the board NACKs "v*IDN?"; the backend asks again.
    stream = ScriptedStream([
        (b"*IDN?\n", b"NACK:Unknown command: 'v*IDN?'\n"), IDN, (b"*RESET\n", b"ACK\n"),
    ])
    board = await Backend.from_stream(stream, port="scripted", serial_number="srABC")
    stream.assert_all_used()
    assert board.firmware_version == "4.4.2"
    await board.close()


async def test_the_simulator_with_leftovers_is_still_identified() -> None:
    sim = SRPowerBoardFw4Simulator("srABC")
    sim.receive(b"v")  # half a line from someone else
    board, _, _ = await connect(sim)
    assert board.firmware_version == "4.4.2"
    await board.close()


class CountingFw4Simulator(SRPowerBoardFw4Simulator):
    """Counts the button reads; presses (latched) when ``ready()`` says."""

    def __init__(self, serial_number: str) -> None:
        super().__init__(serial_number)
        self.button_reads = 0
        self.pressed_at: int | None = None
        self.ready: Any = lambda: False

    def _button(self, args: list[str]) -> str:
        self.button_reads += 1
        if self.pressed_at is None and self.ready():
            self.pressed_at = self.button_reads
            self.click_start()
        return super()._button(args)


async def test_waiters_share_one_stream_of_latch_reads(monkeypatch: pytest.MonkeyPatch) -> None:
    sim = CountingFw4Simulator("srABC")
    board, backend, _ = await connect(sim)
    monkeypatch.setattr(Backend, "BUTTON_POLL_INTERVAL", 0.001)
    watch = backend._presses
    sim.ready = lambda: watch.waiters == 4 and sim.button_reads >= 3
    done = 0

    async def wait() -> None:
        nonlocal done
        await board.start_button.wait_until_pressed()
        done += 1

    async with anyio.create_task_group() as group:
        for _ in range(4):
            group.start_soon(wait)
    assert done == 4
    # One stream (the first read forgets an old press): it stopped at the read that took
    # the press from the latch, which no other read could have seen.
    assert sim.button_reads == sim.pressed_at
    assert not watch.polling
    with pytest.raises(ValueError, match="only start button 0"):
        await backend.wait_until_button_pressed(1)
    await board.close()

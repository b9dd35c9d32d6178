"""Reconnection: a board that vanishes and comes back works again through the same object."""

from __future__ import annotations

from datetime import timedelta
from types import SimpleNamespace
from typing import Any

import anyio
import pytest

from j5aio.backends.hardware import registry
from j5aio.backends.hardware.options import DiscoveryOptions
from j5aio.backends.hardware.reconnect import ReconnectPolicy
from j5aio.backends.hardware.sb.arduino import SBArduinoHardwareBackend
from j5aio.backends.hardware.sr.v4.power_board import SRV4PowerBoardHardwareBackend
from j5aio.backends.hardware.transports.memory import SimulatorStream
from j5aio.boards.sr.v4.power_board import PowerBoard
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.errors import BoardDisconnectionError
from j5aio.simulator import SBArduinoSimulator
from j5aio.simulator.environment import SIMULATED_ENVIRONMENT
from j5aio.simulator.kit import KitConfig, use_kit
from j5aio.testing.reliability import BACKEND_NAMES, replug_trials

QUICK = ReconnectPolicy(interval=0.0)


def comport(device: str, serial_number: str) -> SimpleNamespace:
    return SimpleNamespace(
        device=device,
        vid=0x2341,
        pid=0x0043,
        serial_number=serial_number,
        manufacturer="Arduino (www.arduino.cc)",
        product=None,
        description="Arduino Uno",
    )


async def test_a_board_back_on_another_path_is_the_same_board() -> None:
    sim = SBArduinoSimulator("SER1")
    ports = [comport("/dev/ttyACM0", "SER1")]
    opened: list[str] = []

    async def opener(port: str, baudrate: int) -> Any:
        opened.append(port)
        return SimulatorStream(sim, time_scale=0)

    options = DiscoveryOptions(port_source=lambda: ports, opener=opener, time_scale=0.01)
    (board,) = await SBArduinoHardwareBackend.discover(options=options)
    backend = board.backend
    assert isinstance(backend, SBArduinoHardwareBackend)
    backend.reconnect_policy = QUICK
    await board.setup()
    await board.pins[4].set_mode(GPIOPinMode.DIGITAL_OUTPUT)
    await board.pins[4].digital_write(True)

    sim.unplug()
    ports.clear()
    with pytest.raises(BoardDisconnectionError):
        await board.pins[5].digital_read()
    with pytest.raises(BoardDisconnectionError, match="disconnected"):
        await board.pins[5].digital_read()
    assert not backend.is_connected
    assert registry.holder("/dev/ttyACM0") is board

    ports.append(comport("/dev/ttyACM1", "SER1"))  # the adapter came back elsewhere
    sim.plug()
    sim.set_input_level(5, True)
    assert await board.pins[5].digital_read() is True
    assert opened == ["/dev/ttyACM0", "/dev/ttyACM1"]
    assert backend.port == "/dev/ttyACM1"
    assert registry.holder("/dev/ttyACM1") is board
    assert registry.holder("/dev/ttyACM0") is None
    # The board was reset: the backend forgot pin 4 was a high output.
    assert await board.pins[4].get_mode() is GPIOPinMode.DIGITAL_INPUT
    # Looking again gives the same board, not a second one.
    assert await SBArduinoHardwareBackend.discover(options=options) == [board]
    await board.close()


async def test_a_lost_board_found_by_discovery_is_reconnected_then() -> None:
    sim = SBArduinoSimulator("SER2")
    ports = [comport("/dev/ttyACM0", "SER2")]

    async def opener(port: str, baudrate: int) -> Any:
        return SimulatorStream(sim, time_scale=0)

    options = DiscoveryOptions(port_source=lambda: ports, opener=opener, time_scale=0.01)
    (board,) = await SBArduinoHardwareBackend.discover(options=options)
    sim.unplug()
    with pytest.raises(BoardDisconnectionError):
        await board.pins[14].analogue_read()
    ports[0] = comport("/dev/ttyACM3", "SER2")
    sim.plug()
    assert await SBArduinoHardwareBackend.discover(options=options) == [board]
    assert board.backend.is_connected  # type: ignore[attr-defined]
    await board.close()


async def test_idempotent_calls_retry_once_and_a_buzz_never() -> None:
    kit = use_kit(KitConfig(power_boards=1, motor_boards=0, servo_boards=0, sb_arduinos=0))
    board = (await SIMULATED_ENVIRONMENT.get_board_group(PowerBoard)).singular()
    backend = board.backend
    assert isinstance(backend, SRV4PowerBoardHardwareBackend)
    sim = kit.power_boards[0]
    # A brief brown-out: gone and back before the next call. A read is retried.
    sim.unplug()
    sim.plug()
    assert await board.battery_sensor.get_voltage() == pytest.approx(12.0)
    assert backend.reconnections == 1
    # A note is not: it fails, though the board is back.
    sim.unplug()
    sim.plug()
    with pytest.raises(BoardDisconnectionError):
        await backend.buzz(0, timedelta(seconds=0.1), 440)
    assert sim.note_queue == []
    await anyio.sleep(backend.reconnect_policy.interval)
    assert await board.battery_sensor.get_voltage() == pytest.approx(12.0)  # found again
    backend.reconnect_policy = ReconnectPolicy(interval=0.0, retry_idempotent=False)
    sim.unplug()
    sim.plug()
    with pytest.raises(BoardDisconnectionError):
        await board.battery_sensor.get_voltage()
    assert await board.battery_sensor.get_voltage() == pytest.approx(12.0)  # back by now
    await board.close()


async def test_a_retry_waits_for_the_board_as_long_as_the_policy_says() -> None:
    kit = use_kit(KitConfig(power_boards=1, motor_boards=0, servo_boards=0, sb_arduinos=0))
    board = (await SIMULATED_ENVIRONMENT.get_board_group(PowerBoard)).singular()
    backend = board.backend
    assert isinstance(backend, SRV4PowerBoardHardwareBackend)
    backend.reconnect_policy = ReconnectPolicy(interval=0.01, retry_wait=2.0)
    sim = kit.power_boards[0]
    sim.unplug()

    async def plug_later() -> None:
        await anyio.sleep(0.1)
        sim.plug()

    async with anyio.create_task_group() as group:
        group.start_soon(plug_later)
        await backend.set_power_output_enabled(0, True)
    assert sim.outputs[0] is True
    await board.close()


async def test_a_board_with_reconnection_off_stays_lost_and_frees_its_port() -> None:
    kit = use_kit(KitConfig(power_boards=1, motor_boards=0, servo_boards=0, sb_arduinos=0))
    board = (await SIMULATED_ENVIRONMENT.get_board_group(PowerBoard)).singular()
    backend = board.backend
    assert isinstance(backend, SRV4PowerBoardHardwareBackend)
    backend.reconnect_policy = ReconnectPolicy(enabled=False)
    kit.power_boards[0].unplug()
    with pytest.raises(BoardDisconnectionError):
        await board.battery_sensor.get_voltage()
    assert registry.holder(backend.port) is None
    kit.power_boards[0].plug()
    with pytest.raises(BoardDisconnectionError):
        await board.battery_sensor.get_voltage()
    assert not await backend.reconnect() or backend.is_connected
    await board.close()
    assert not await backend.reconnect()


def test_a_policy_refuses_bad_values() -> None:
    with pytest.raises(ValueError, match="interval"):
        ReconnectPolicy(interval=-1)
    with pytest.raises(ValueError, match="retry_wait"):
        ReconnectPolicy(retry_wait=float("inf"))
    backend: Any = SRV4PowerBoardHardwareBackend
    with pytest.raises(TypeError, match="ReconnectPolicy"):
        backend.reconnect_policy.fset(object(), "fast")


async def test_a_stream_backend_cannot_be_reopened() -> None:
    sim = SBArduinoSimulator("S3")
    board = await SBArduinoHardwareBackend.from_stream(
        SimulatorStream(sim, time_scale=0), port="s", serial_number="S3", time_scale=0.01
    )
    board.backend.reconnect_policy = QUICK  # type: ignore[attr-defined]
    sim.unplug()
    with pytest.raises(BoardDisconnectionError):
        await board.pins[14].analogue_read()
    sim.plug()
    with pytest.raises(BoardDisconnectionError, match="disconnected"):
        await board.pins[14].analogue_read()
    await board.close()


@pytest.mark.parametrize("name", BACKEND_NAMES)
async def test_r3_replugged_boards_answer_again_with_nothing_stale(name: str) -> None:
    report = await replug_trials(name, 3, seed=5)
    assert report.trials == report.disconnection_errors == 3
    assert (report.wrong_outcomes, report.stale, report.duplicates) == (0, 0, 0), report.details
    assert report.make_safe_failures == 0
    assert len(report.back_after) == 3
    assert max(report.back_after) < 5  # liveness only; the bench measures the time

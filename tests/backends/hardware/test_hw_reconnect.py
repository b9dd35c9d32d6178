"""Reconnection: a board that vanishes and comes back works again through the same object."""

from __future__ import annotations

import logging
from datetime import timedelta
from types import SimpleNamespace
from typing import Any

import anyio
import pytest

from j5aio.backends.acknowledgements import acknowledge_later
from j5aio.backends.hardware import registry
from j5aio.backends.hardware.options import DiscoveryOptions
from j5aio.backends.hardware.reconnect import Reconnecting, ReconnectPolicy
from j5aio.backends.hardware.sb.arduino import SBArduinoHardwareBackend
from j5aio.backends.hardware.sb.arduino_2024 import SBArduino2024HardwareBackend
from j5aio.backends.hardware.sr.v4.motor_board_fw4 import SRV4MotorBoardFw4HardwareBackend
from j5aio.backends.hardware.sr.v4.motor_fw4_codec import parse_status
from j5aio.backends.hardware.sr.v4.power_board import SRV4PowerBoardHardwareBackend
from j5aio.backends.hardware.sr.v4.servo_board import SRV4ServoBoardHardwareBackend
from j5aio.backends.hardware.transports.memory import SimulatorStream
from j5aio.backends.hardware.transports.readers import read_line
from j5aio.backends.safe_state_pass import claim_attempt, safe_state_pass
from j5aio.boards.board import Board
from j5aio.boards.sr.v4.motor_board_fw4 import MotorBoardFw4
from j5aio.boards.sr.v4.power_board import PowerBoard
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.components.motor import MotorSpecialState
from j5aio.errors import BoardDisconnectionError
from j5aio.simulator import (
    PinMode,
    SBArduino2024Simulator,
    SBArduinoSimulator,
    SRMotorBoardFw4Simulator,
)
from j5aio.simulator.environment import SIMULATED_ENVIRONMENT
from j5aio.simulator.kit import KitConfig, use_kit
from j5aio.testing.transports import FaultyStream
from tests.dataclass_twins import assert_like_generated
from tests.testing.reliability_rig import BACKEND_NAMES, replug_trials

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
    # Discovery opened the shared port twice (the sb2024 kind's probe, then this kind);
    # reconnection opened the new path once.
    assert opened == ["/dev/ttyACM0", "/dev/ttyACM0", "/dev/ttyACM1"]
    assert backend.port == "/dev/ttyACM1"
    assert registry.holder("/dev/ttyACM1") is board
    assert registry.holder("/dev/ttyACM0") is None
    # The board was reset: the backend forgot pin 4 was a high output.
    assert await board.pins[4].get_mode() is GPIOPinMode.DIGITAL_INPUT
    # Looking again gives the same board, not a second one.
    assert await SBArduinoHardwareBackend.discover(options=options) == [board]
    await board.close()


async def _discovered_then_lost(
    serial_number: str,
) -> tuple[SBArduinoSimulator, list[SimpleNamespace], DiscoveryOptions, Any]:
    """Discover a simulated Arduino on a listed port, then unplug it and notice."""
    sim = SBArduinoSimulator(serial_number)
    ports = [comport("/dev/ttyACM0", serial_number)]

    async def opener(port: str, baudrate: int) -> Any:
        return SimulatorStream(sim, time_scale=0)

    options = DiscoveryOptions(port_source=lambda: ports, opener=opener, time_scale=0.01)
    (board,) = await SBArduinoHardwareBackend.discover(options=options)
    sim.unplug()
    with pytest.raises(BoardDisconnectionError):
        await board.pins[14].analogue_read()
    return sim, ports, options, board


async def test_a_lost_board_found_by_discovery_is_reconnected_then() -> None:
    sim, ports, options, board = await _discovered_then_lost("SER2")
    ports[0] = comport("/dev/ttyACM3", "SER2")
    sim.plug()
    assert await SBArduinoHardwareBackend.discover(options=options) == [board]
    assert board.backend.is_connected
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


class _Bus:
    """A stand-in USB bus: the devices it lists, found as ``usb.core.find`` would."""

    def __init__(self, *devices: Any) -> None:
        self.devices = list(devices)

    def __call__(self, *, find_all: bool, idVendor: int, idProduct: int) -> list[Any]:  # noqa: N803
        return [d for d in self.devices if (d.idVendor, d.idProduct) == (idVendor, idProduct)]


class _Unreadable:
    """A device whose serial number cannot be read (it vanished while being looked at)."""

    idVendor = 0x1BDA  # noqa: N815
    idProduct = 0x0010  # noqa: N815
    bus = 9
    address = 9

    @property
    def serial_number(self) -> str:
        raise OSError(19, "No such device")

    def ctrl_transfer(self, *args: Any, **kwargs: Any) -> Any:
        raise OSError(19, "No such device")


class _Placed:
    """A simulator at a place on the stand-in bus (a new place after each replug)."""

    def __init__(self, simulator: Any, address: int) -> None:
        self._simulator = simulator
        self._connection = simulator.connection
        self.bus = 1
        self.address = address

    def __getattr__(self, name: str) -> Any:
        return getattr(self._simulator, name)

    def ctrl_transfer(self, *args: Any, **kwargs: Any) -> Any:
        if self._simulator.connection != self._connection:
            raise OSError(19, "No such device")
        return self._simulator.ctrl_transfer(*args, **kwargs)


async def test_a_usb_board_is_found_again_among_other_devices_at_a_new_address() -> None:
    from j5aio.simulator.sr_power_fw3 import SRPowerBoardFw3Simulator

    ours, theirs, stranger = (SRPowerBoardFw3Simulator(n) for n in ("OURS", "THEIRS", "NEW"))
    bus = _Bus(_Placed(ours, 1), _Placed(theirs, 2))
    options = DiscoveryOptions(usb_finder=bus)
    boards = await SRV4PowerBoardHardwareBackend.discover(options=options)
    board = next(b for b in boards if b.serial_number == "OURS")
    backend = board.backend
    assert isinstance(backend, SRV4PowerBoardHardwareBackend)
    backend.reconnect_policy = QUICK
    assert await backend.reconnect()  # connected: nothing to do
    ours.unplug()
    with pytest.raises(BoardDisconnectionError):
        await backend.set_power_output_enabled(0, True)
    # Back at a new address, after a stranger and an unreadable device; the other
    # board's device is held, so it is not even looked at.
    ours.plug()
    bus.devices = [_Placed(theirs, 2), _Placed(stranger, 3), _Unreadable(), _Placed(ours, 7)]
    await backend.set_power_output_enabled(0, True)
    assert ours.outputs[0] is True
    assert backend.port == "usb:1bda:0010@1.7"
    assert registry.holder("usb:1bda:0010@1.7") is board
    assert registry.holder("usb:1bda:0010@1.1") is None
    for each in boards:
        await each.close()


async def test_a_usb_board_whose_handshake_fails_on_return_stays_lost_until_it_passes() -> None:
    from j5aio.simulator.sr_servo_fw2 import SRServoBoardFw2Simulator

    sim = SRServoBoardFw2Simulator("SERVO")
    bus = _Bus(_Placed(sim, 1))
    options = DiscoveryOptions(usb_finder=bus)
    (board,) = await SRV4ServoBoardHardwareBackend.discover(options=options)
    backend = board.backend
    assert isinstance(backend, SRV4ServoBoardHardwareBackend)
    backend.reconnect_policy = QUICK
    sim.unplug()
    with pytest.raises(BoardDisconnectionError):
        await backend.set_servo_position(0, 0.5)
    sim.has_12v = False  # back on USB, but without its 12 V it cannot start
    sim.plug()
    bus.devices = [_Placed(sim, 2)]
    with pytest.raises(BoardDisconnectionError):
        await backend.set_servo_position(0, 0.5)
    assert not backend.is_connected
    sim.has_12v = True
    sim.power_cycle()
    bus.devices = [_Placed(sim, 3)]
    await backend.set_servo_position(0, 0.5)
    assert sim.positions[0] == 50
    await board.close()


async def test_a_serial_board_whose_handshake_fails_on_return_stays_lost_until_it_passes() -> None:
    from j5aio.testing.transports import ScriptedStream

    sim = SBArduinoSimulator("FLAKY")
    nonsense = [False]

    async def opener(port: str, baudrate: int) -> Any:
        if nonsense[0]:  # the board comes back talking nonsense once
            nonsense[0] = False
            return ScriptedStream([], banner=b"# Hello\n# SBDuino GPIO v2019.8.0\r\n")
        return SimulatorStream(sim, time_scale=0)

    board = await SBArduinoHardwareBackend.attach("/dev/flaky", opener=opener, time_scale=0.01)
    backend = board.backend
    assert isinstance(backend, SBArduinoHardwareBackend)
    backend.reconnect_policy = QUICK
    sim.unplug()
    with pytest.raises(BoardDisconnectionError):
        await board.pins[14].analogue_read()
    nonsense[0] = True
    sim.plug()
    with pytest.raises(BoardDisconnectionError):
        await board.pins[14].analogue_read()
    assert not nonsense[0] and not backend.is_connected
    assert 0 <= await board.pins[14].analogue_read() <= 5
    await board.close()


async def test_a_serial_board_with_reconnection_off_frees_its_port() -> None:
    sim = SBArduinoSimulator("OFF")

    async def opener(port: str, baudrate: int) -> Any:
        return SimulatorStream(sim, time_scale=0)

    board = await SBArduinoHardwareBackend.attach("/dev/off", opener=opener, time_scale=0.01)
    board.backend.reconnect_policy = ReconnectPolicy(enabled=False)  # type: ignore[attr-defined]
    sim.unplug()
    with pytest.raises(BoardDisconnectionError):
        await board.pins[14].analogue_read()
    assert registry.holder("/dev/off") is None
    await board.close()


async def test_looking_with_another_search_does_not_take_over_a_lost_board() -> None:
    sim, ports, options, board = await _discovered_then_lost("SER9")
    sim.plug()
    other = DiscoveryOptions(
        port_source=lambda: list(ports), opener=options.opener, time_scale=0.01
    )
    # Its port is still held by the lost board, which is handed back as it is.
    assert await SBArduinoHardwareBackend.discover(options=other) == [board]
    await board.close()


def usb_port(
    device: str, serial_number: str, vid: int, pid: int, **strings: str
) -> SimpleNamespace:
    fields: dict[str, object] = {"manufacturer": None, "product": None, "description": ""}
    fields.update(strings)
    return SimpleNamespace(device=device, vid=vid, pid=pid, serial_number=serial_number, **fields)


async def test_a_replugged_fw4_motor_board_forgets_what_it_sent_and_works_again() -> None:
    sim = SRMotorBoardFw4Simulator("srM1")
    ports = [
        usb_port(
            "/dev/ttyUSB0", "srM1", 0x0403, 0x6001, manufacturer="Student Robotics", product="MCV4B"
        )
    ]

    async def opener(port: str, baudrate: int) -> Any:
        return SimulatorStream(sim, time_scale=0)

    options = DiscoveryOptions(port_source=lambda: ports, opener=opener, time_scale=0.01)
    (board,) = await SRV4MotorBoardFw4HardwareBackend.discover(options=options)
    assert isinstance(board, MotorBoardFw4)
    backend = board.backend
    assert isinstance(backend, SRV4MotorBoardFw4HardwareBackend)
    backend.reconnect_policy = QUICK
    await board.setup()
    await board.motors[0].set_power(MotorSpecialState.BRAKE)
    assert backend.last_sent[0] is MotorSpecialState.BRAKE

    sim.unplug()
    ports.clear()
    with pytest.raises(BoardDisconnectionError):
        await board.motors[1].get_power()
    ports.append(
        usb_port(
            "/dev/ttyUSB1", "srM1", 0x0403, 0x6001, manufacturer="Student Robotics", product="MCV4B"
        )
    )
    sim.plug()
    await board.motors[1].set_power(0.25)
    assert backend.port == "/dev/ttyUSB1"
    assert backend.last_sent == [None, 0.25]  # what was sent before is forgotten
    assert sim.motors[1].value == 250
    assert await board.motors[0].get_power() is MotorSpecialState.BRAKE  # read from the board
    await board.close()


async def test_a_replugged_sb2024_arduino_forgets_its_pins_and_works_again() -> None:
    sim = SBArduino2024Simulator("SB24")
    ports = [comport("/dev/ttyACM0", "SB24")]

    async def opener(port: str, baudrate: int) -> Any:
        return SimulatorStream(sim, time_scale=0)

    options = DiscoveryOptions(port_source=lambda: ports, opener=opener, time_scale=0.01)
    (board,) = await SBArduino2024HardwareBackend.discover(options=options)
    backend = board.backend
    assert isinstance(backend, SBArduino2024HardwareBackend)
    backend.reconnect_policy = QUICK
    await board.setup()
    await board.pins[4].set_mode(GPIOPinMode.DIGITAL_OUTPUT)
    await board.pins[4].digital_write(True)

    sim.unplug()
    ports[0] = comport("/dev/ttyACM1", "SB24")
    with pytest.raises(BoardDisconnectionError):
        await board.pins[5].digital_read()
    sim.plug()
    sim.set_input_level(5, True)
    assert await board.pins[5].digital_read() is True
    assert backend.port == "/dev/ttyACM1"
    # The board rebooted: pin 4 is an input again, and the backend knows it.
    assert await board.pins[4].get_mode() is GPIOPinMode.DIGITAL_INPUT
    assert sim.pin_mode(4) is PinMode.INPUT
    await board.close()


async def test_a_board_back_just_before_the_end_is_still_made_safe() -> None:
    """The program ends at once after the failed call: the rate limit must not stop make_safe."""
    sim = SRMotorBoardFw4Simulator("srM2")
    ports = [
        usb_port(
            "/dev/ttyUSB0", "srM2", 0x0403, 0x6001, manufacturer="Student Robotics", product="MCV4B"
        )
    ]

    async def opener(port: str, baudrate: int) -> Any:
        return SimulatorStream(sim, time_scale=0)

    options = DiscoveryOptions(port_source=lambda: ports, opener=opener, time_scale=0.01)
    (board,) = await SRV4MotorBoardFw4HardwareBackend.discover(options=options)
    assert isinstance(board, MotorBoardFw4)
    backend = board.backend
    assert isinstance(backend, SRV4MotorBoardFw4HardwareBackend)
    # However long the limit, the pass that makes the boards safe tries once more.
    backend.reconnect_policy = ReconnectPolicy(interval=3600)
    await board.setup()
    await board.motors[0].set_power(0.5)

    sim.unplug()
    with pytest.raises(BoardDisconnectionError):
        await board.motors[1].get_power()
    sim.plug()  # the board is on the battery: it kept driving, and is back
    assert sim.motors[0].value == 500
    with pytest.raises(BoardDisconnectionError, match="disconnected"):
        await board.motors[1].get_power()  # the limit holds outside the pass
    assert await Board.make_all_safe() == []
    assert (sim.motors[0].enabled, sim.motors[0].value) == (True, 0)  # braked
    assert backend.reconnections == 1
    await board.close()


async def test_the_pass_gives_each_lost_board_one_try() -> None:
    first, second = object(), object()
    assert not claim_attempt(first)  # outside a pass: never
    with safe_state_pass():
        assert claim_attempt(first)
        assert not claim_attempt(first)
        assert claim_attempt(second)
        with safe_state_pass():  # a pass of its own starts afresh
            assert claim_attempt(first)
    assert not claim_attempt(second)


async def test_a_call_cut_short_by_closing_the_board_is_not_a_vanished_board(
    caplog: pytest.LogCaptureFixture,
) -> None:
    """At game over the ports are closed under the program's feet: that is no unplug."""
    sim = SRMotorBoardFw4Simulator("srM3")
    faulty = FaultyStream(SimulatorStream(sim, time_scale=0))
    board = await SRV4MotorBoardFw4HardwareBackend.from_stream(
        faulty, port="sim", serial_number="srM3"
    )
    backend = board.backend
    assert isinstance(backend, SRV4MotorBoardFw4HardwareBackend)
    faulty.silence()  # the reply to the call in flight does not come before the end
    failures: list[BaseException] = []

    async def in_flight() -> None:
        try:
            await backend.get_motor_current(0)
        except BoardDisconnectionError as exc:
            failures.append(exc)

    with caplog.at_level(logging.INFO, "j5aio"):
        async with anyio.create_task_group() as group:
            group.start_soon(in_flight)
            await anyio.sleep(0.02)  # the request has gone
            board.close_now()  # as the match timer does
    assert len(failures) == 1
    assert "vanished" not in caplog.text
    assert not backend.is_connected


class _Vanishing(Reconnecting):
    """The smallest reconnecting backend: its board never comes back."""

    RECONNECT_POLICY = ReconnectPolicy(interval=3600)

    async def _reopen(self) -> None:
        raise BoardDisconnectionError("not back")


async def test_a_guarded_call_that_fails_for_good_forgets_the_board_by_default() -> None:
    backend = _Vanishing()
    calls: list[str] = []

    async def vanish() -> None:
        calls.append("call")
        raise BoardDisconnectionError("gone")

    with pytest.raises(BoardDisconnectionError, match="gone"):
        await backend._guarded(vanish, idempotent=True)
    assert calls == ["call"]  # not back at once: no retry
    assert not backend.is_connected
    with pytest.raises(BoardDisconnectionError, match="the board is disconnected"):
        await backend._guarded(vanish, idempotent=True)
    assert calls == ["call"]  # a lost board is not called


async def test_a_brown_out_on_the_fw4_hot_paths_retries_what_may_be_repeated() -> None:
    # Commands and queries go straight to the link while the board is there; a board
    # that vanished under them is handled as any guarded call: found again, and the
    # call retried if it may be repeated.
    sim = SRMotorBoardFw4Simulator("srM2")
    ports = [
        usb_port(
            "/dev/ttyUSB0", "srM2", 0x0403, 0x6001, manufacturer="Student Robotics", product="MCV4B"
        )
    ]

    async def opener(port: str, baudrate: int) -> Any:
        return SimulatorStream(sim, time_scale=0)

    options = DiscoveryOptions(port_source=lambda: ports, opener=opener, time_scale=0.01)
    (board,) = await SRV4MotorBoardFw4HardwareBackend.discover(options=options)
    assert isinstance(board, MotorBoardFw4)
    backend = board.backend
    assert isinstance(backend, SRV4MotorBoardFw4HardwareBackend)
    backend.reconnect_policy = QUICK
    await board.setup()
    sim.unplug()
    sim.plug()
    await board.motors[0].set_power(0.5)  # a command, retried on the board that came back
    assert sim.motors[0].value == 500
    assert backend.reconnections == 1
    sim.unplug()
    sim.plug()
    assert await board.motors[1].get_power() is MotorSpecialState.COAST  # a query, retried
    assert backend.reconnections == 2
    sim.unplug()
    sim.plug()
    status = await backend._query_then(  # retried too
        b"*STATUS?\n", lambda reply: parse_status(backend.board.name, reply)
    )
    assert status.faults == (False, False)
    assert backend.reconnections == 3
    # An acknowledgement owed when the board vanished is not asked for again: the call
    # that was to read it fails, and the next finds the board again.
    with acknowledge_later():
        await board.motors[0].set_power(0.25)
        assert backend.owes_acknowledgement()
        sim.unplug()
        sim.plug()
        with pytest.raises(BoardDisconnectionError, match="acknowledgement of the earlier"):
            await board.motors[0].get_power()
        assert not backend.owes_acknowledgement() and not backend.is_connected
        await board.motors[0].get_power()  # the board is found again
        assert backend.is_connected and backend.reconnections == 4
    # A call to a board known to be lost looks for it first.
    for call in (
        lambda: board.motors[0].set_power(0.75),
        lambda: backend._query_then(b"*STATUS?\n", lambda reply: reply),
        lambda: backend.command(b"MOT:1:SET:100\n", read_line()),
        backend.confirm_acknowledgement,
    ):
        sim.unplug()
        with pytest.raises(BoardDisconnectionError):
            await board.motors[1].get_power()
        assert not backend.is_connected
        sim.plug()
        await call()
        assert backend.is_connected
    assert sim.motors[0].value == 750 and sim.motors[1].value == 100
    assert backend.reconnections == 8
    sim.unplug()
    sim.plug()
    await backend.command(b"MOT:1:SET:200\n", read_line())  # a backend's command, retried
    assert sim.motors[1].value == 200 and backend.reconnections == 9
    await board.close()


async def test_a_brown_out_under_a_fw3_button_wait_is_retried() -> None:
    kit = use_kit(KitConfig(power_boards=1, motor_boards=0, servo_boards=0, sb_arduinos=0))
    board = (await SIMULATED_ENVIRONMENT.get_board_group(PowerBoard)).singular()
    backend = board.backend
    assert isinstance(backend, SRV4PowerBoardHardwareBackend)
    sim = kit.power_boards[0]
    sim.unplug()
    sim.plug()
    sim.press_start()
    with anyio.fail_after(5):
        await board.start_button.wait_until_pressed()  # the poll is retried
    assert backend.reconnections == 1
    backend.reconnect_policy = ReconnectPolicy(interval=0.0, retry_idempotent=False)
    sim.unplug()
    with pytest.raises(BoardDisconnectionError):
        await board.battery_sensor.get_voltage()
    assert not backend.is_connected
    sim.plug()
    with anyio.fail_after(5):
        await board.start_button.wait_until_pressed()  # a lost board is looked for first
    assert backend.is_connected and backend.reconnections == 2
    await board.close()


def test_the_reconnect_policy_is_the_generated_dataclass() -> None:
    assert_like_generated(
        ReconnectPolicy,
        [((), {}), ((False, 0.5, False, 2.0), {}), ((), {"interval": 0, "retry_wait": 1})],
    )
    bad: list[tuple[str, Any]] = [
        ("interval", -0.1),
        ("retry_wait", float("inf")),
        ("interval", "1"),
    ]
    for name, value in bad:
        with pytest.raises(ValueError, match=f"{name} must be a finite number of seconds >= 0"):
            ReconnectPolicy(**{name: value})

"""Acknowledgements confirmed later: a command returns once written, its reply is checked next.

Every firmware generation with commands whose reply only acknowledges them is driven
through the same checks: the command returns with its acknowledgement owed, and what the
backend remembers changes only when that acknowledgement is read (before the board's
next request); a refusal or a missing acknowledgement is raised by the next request as
:class:`~j5aio.errors.EarlierCommandError`, which is then not sent; closing the board, or
making it safe, reads what is owed; cancellation and late replies leave the link in step.
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Awaitable, Callable
from dataclasses import dataclass
from typing import Any, ClassVar

import anyio
import pytest

from j5aio.backends import acknowledge_later, acknowledging_later
from j5aio.backends.hardware.options import DiscoveryOptions
from j5aio.backends.hardware.sb.arduino import SBArduinoHardwareBackend
from j5aio.backends.hardware.serial_backend import SerialHardwareBackend
from j5aio.backends.hardware.sr.v4.motor_board_fw4 import SRV4MotorBoardFw4HardwareBackend
from j5aio.backends.hardware.sr.v4.ruggeduino import SRV4RuggeduinoHardwareBackend
from j5aio.backends.hardware.transports.memory import SimulatorStream
from j5aio.backends.hardware.transports.serial_link import SerialLink
from j5aio.backends.safe_state_pass import safe_state_pass
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.components.motor import MotorSpecialState
from j5aio.errors import (
    BoardDisconnectionError,
    CommunicationTimeoutError,
    EarlierCommandError,
    UnexpectedReplyError,
)
from j5aio.simulator import (
    SBArduino2024Simulator,
    SBArduinoSimulator,
    SRMotorBoardFw4Simulator,
    SRPowerBoardFw4Simulator,
    SRServoBoardFw4Simulator,
)
from j5aio.simulator.sr_ruggeduino_fw1 import SRRuggeduinoSimulator
from j5aio.testing.transports import FaultyStream, RecordingStream
from tests.backends.hardware.test_hw_late_replies_today import (
    TIMEOUT,
    QuickMotor,
    QuickPower,
    QuickSB2024,
    QuickServo,
    QuickSRArduino,
)
from tests.backends.hardware.test_hw_reconnect import QUICK, usb_port
from tests.testing.reliability_rig import cancellation_trials


class QuickRuggeduino(SRV4RuggeduinoHardwareBackend):
    DEFAULT_TIMEOUT: ClassVar[float] = TIMEOUT


class QuickSB2019(SBArduinoHardwareBackend):
    DEFAULT_TIMEOUT: ClassVar[float] = TIMEOUT


Call = Callable[[Any], Awaitable[object]]


@dataclass
class Case:
    """One firmware generation: an ack-only command, a query, and what the command changes."""

    sim: Any
    backend: type[SerialHardwareBackend]
    act: Call  # an ack-only command
    ask: Call  # a query, whose answer is `expected`
    expected: object
    remembered: Callable[[Any], bool]  # whether the backend has noted `act`
    refused: bytes  # an ack-only command the board refuses (fw 4 text boards)
    prepare: Call | None = None


def _power() -> Case:
    sim = SRPowerBoardFw4Simulator("srP1")
    sim.battery_voltage = 11.5
    return Case(
        sim, QuickPower,
        lambda b: b.set_power_output_enabled(0, True),
        lambda b: b.get_battery_sensor_voltage(0), 11.5,
        lambda b: True,  # outputs are read back from the board, not remembered
        b"OUT:9:SET:1\n",
    )


def _motor() -> Case:
    sim = SRMotorBoardFw4Simulator("srM1")
    sim.input_voltage = 11.5
    return Case(
        sim, QuickMotor,
        lambda b: b.set_motor_state(0, 0.5),
        lambda b: b.get_voltage_sensor_voltage(0), 11.5,
        lambda b: b.last_sent[0] == 0.5,
        b"MOT:7:SET:100\n",
    )


def _servo() -> Case:
    sim = SRServoBoardFw4Simulator("srS1")
    sim.set_supply(voltage=6.0, current=0.75)
    return Case(
        sim, QuickServo,
        lambda b: b.set_servo_position(0, 0.5),
        lambda b: b.get_supply_current(0), 0.75,
        lambda b: True,  # the position is read back from the board, not remembered
        b"SERVO:99:SET:1500\n",
    )


async def _output_pin(backend: Any) -> None:
    await backend.set_gpio_pin_mode(4, GPIOPinMode.DIGITAL_OUTPUT)
    await backend.set_gpio_pin_mode(14, GPIOPinMode.ANALOGUE_INPUT)


def _arduino(sim: Any, backend: type[SerialHardwareBackend], refused: bytes) -> Case:
    sim.set_analogue(14, raw=512)
    return Case(
        sim, backend,
        lambda b: b.write_gpio_pin_digital_state(4, True),
        lambda b: b.read_gpio_pin_analogue_value(14), pytest.approx(2.5, abs=0.01),
        lambda b: b._pins.state(4).level is True,
        refused,
        _output_pin,
    )


def _sr_arduino() -> Case:
    return _arduino(SRRuggeduinoSimulator("A1", firmware_version=2), QuickSRArduino, b"")


def _sb2024() -> Case:
    return _arduino(SBArduino2024Simulator("A2"), QuickSB2024, b"")


def _ruggeduino() -> Case:
    sim = SRRuggeduinoSimulator("A3")
    sim.set_analogue(14, raw=512)
    return Case(
        sim, QuickRuggeduino,
        lambda b: b.write_gpio_pin_digital_state(4, True),
        lambda b: b.read_gpio_pin_analogue_value(14), pytest.approx(2.5, abs=0.01),
        lambda b: b._pins.state(4).level is True,
        b"",
        _output_pin,
    )


def _sb2019() -> Case:
    sim = SBArduinoSimulator("A4")
    return Case(
        sim, QuickSB2019,
        lambda b: b.set_servo_position(0, 0.5),
        lambda b: b.read_gpio_pin_digital_state(5), True,
        lambda b: b._servos[0] == 0.5,
        b"",
        lambda b: b.set_gpio_pin_mode(5, GPIOPinMode.DIGITAL_INPUT_PULLUP),
    )


CASES = {
    "power-fw4": _power,
    "motor-fw4": _motor,
    "servo-fw4": _servo,
    "sr-arduino-fw2": _sr_arduino,
    "sb2024": _sb2024,
    "ruggeduino-fw1": _ruggeduino,
    "sb2019": _sb2019,
}
#: The generations whose firmware refuses a command (NACK); the Arduinos' refusal is a
#: reply that is not an acknowledgement (see the corrupted replies below).
REFUSING = ["power-fw4", "motor-fw4", "servo-fw4"]


async def _connect(name: str) -> tuple[Case, Any, FaultyStream, RecordingStream]:
    case = CASES[name]()
    faulty = FaultyStream(SimulatorStream(case.sim, time_scale=0))
    recording = RecordingStream(faulty)
    board = await case.backend.from_stream(recording, port="sim", serial_number="S1")
    await board.setup()
    if case.prepare is not None:
        await case.prepare(board.backend)
    recording.clear()
    return case, board, faulty, recording


def test_the_switch_is_off_by_default_and_scoped() -> None:
    assert not acknowledging_later()
    with acknowledge_later():
        assert acknowledging_later()
        with acknowledge_later(False):
            assert not acknowledging_later()
        assert acknowledging_later()
    assert not acknowledging_later()


async def test_tasks_started_inside_the_switch_inherit_it() -> None:
    seen: list[bool] = []

    async def note() -> None:
        seen.append(acknowledging_later())

    with acknowledge_later():
        async with anyio.create_task_group() as group:
            group.start_soon(note)
    async with anyio.create_task_group() as group:
        group.start_soon(note)
    assert seen == [True, False]


@pytest.mark.parametrize("name", list(CASES))
async def test_by_default_a_command_waits_for_its_acknowledgement(name: str) -> None:
    case, board, _, _ = await _connect(name)
    backend = board.backend
    await case.act(backend)
    assert backend.link.acknowledgement_owed is None
    assert case.remembered(backend)
    await board.close()


@pytest.mark.parametrize("name", list(CASES))
async def test_a_command_returns_once_written_and_is_confirmed_before_the_next(
    name: str,
) -> None:
    case, board, _, recording = await _connect(name)
    backend = board.backend
    with acknowledge_later():
        await case.act(backend)
        owed = backend.link.acknowledgement_owed
        assert owed is not None and recording.sent.endswith(owed)
        assert await case.ask(backend) == case.expected
    assert backend.link.acknowledgement_owed is None
    assert case.remembered(backend)
    assert not backend.link.is_dirty
    await board.close()


async def test_the_cache_changes_only_when_the_acknowledgement_is_read() -> None:
    _, board, _, _ = await _connect("motor-fw4")
    backend = board.backend
    with acknowledge_later():
        await backend.set_motor_state(1, MotorSpecialState.BRAKE)
        assert backend.last_sent[1] is None
        await backend.get_voltage_sensor_voltage(0)
    assert backend.last_sent[1] is MotorSpecialState.BRAKE
    await board.close()


@pytest.mark.parametrize("name", REFUSING)
async def test_a_refusal_found_later_is_raised_by_the_next_request(
    name: str, caplog: pytest.LogCaptureFixture
) -> None:
    case, board, _, recording = await _connect(name)
    backend = board.backend
    with acknowledge_later():
        await backend._act(case.refused)
        recording.clear()
        with (
            caplog.at_level(logging.WARNING),
            pytest.raises(EarlierCommandError, match="earlier command") as raised,
        ):
            await case.ask(backend)
        assert raised.value.command == case.refused
        assert repr(case.refused[:8])[2:-1] in str(raised.value)
        assert "not this one" in str(raised.value)
        assert recording.sent == b""  # the next request was not sent
        assert any("failed" in record.getMessage() for record in caplog.records)
        assert await case.ask(backend) == case.expected  # and the link is in step
    await board.close()


@pytest.mark.parametrize("name", list(CASES))
async def test_a_wrong_acknowledgement_found_later_is_raised_and_leaves_no_trace(
    name: str,
) -> None:
    case, board, faulty, _ = await _connect(name)
    backend = board.backend
    if name == "sb2019":
        case.remembered = lambda b: b._servos[0] == 0.5
    with acknowledge_later():
        faulty.corrupt_next_reply()
        await case.act(backend)
        with pytest.raises(EarlierCommandError) as raised:
            await case.ask(backend)
        # (the SR Arduinos' acknowledgement is a bare line ending: corrupted, it never ends)
        bare = name in ("ruggeduino-fw1", "sr-arduino-fw2")
        cause = CommunicationTimeoutError if bare else UnexpectedReplyError
        assert isinstance(raised.value.__cause__, cause)
        assert not case.remembered(backend) or name in ("servo-fw4", "power-fw4")
        assert await case.ask(backend) == case.expected
    await board.close()


@pytest.mark.parametrize("late_by", [0.02, None])
@pytest.mark.parametrize("name", list(CASES))
async def test_a_missing_acknowledgement_is_raised_later_and_a_late_one_is_not_taken(
    name: str, late_by: float | None
) -> None:
    case, board, faulty, _ = await _connect(name)
    backend = board.backend
    with acknowledge_later():
        if late_by is None:  # (an SB 2019 reply has an echo line: drop all of it)
            faulty.drop_next_reply(None if name == "sb2019" else b"\n")
        else:
            faulty.delay_next_reply(TIMEOUT + late_by)
        await case.act(backend)
        with pytest.raises(EarlierCommandError, match="earlier command") as raised:
            await case.ask(backend)
        assert isinstance(raised.value.__cause__, CommunicationTimeoutError)
        # A late acknowledgement arrives while this request waits: it is not its answer.
        assert await case.ask(backend) == case.expected
        await case.act(backend)
        assert await case.ask(backend) == case.expected
    assert case.remembered(backend)
    await board.close()


@pytest.mark.parametrize("name", list(CASES))
async def test_closing_reads_what_is_owed(name: str) -> None:
    case, board, _, _ = await _connect(name)
    backend = board.backend
    with acknowledge_later():
        await case.act(backend)
    assert backend.link.acknowledgement_owed is not None
    await board.close()
    assert backend.link.acknowledgement_owed is None
    assert case.remembered(backend)


async def test_a_failure_found_at_close_is_logged_not_raised(
    caplog: pytest.LogCaptureFixture,
) -> None:
    _, board, faulty, _ = await _connect("motor-fw4")
    with acknowledge_later():
        faulty.drop_next_reply()
        await board.backend.set_motor_state(0, 0.25)
    with caplog.at_level(logging.WARNING):
        await board.close()
    assert any("MOT:0:SET:250" in record.getMessage() for record in caplog.records)
    assert board.backend.last_sent[0] is None


async def test_making_safe_sends_the_safe_state_even_after_a_failure_found_then(
    caplog: pytest.LogCaptureFixture,
) -> None:
    case, board, faulty, _ = await _connect("motor-fw4")
    sim = case.sim
    with acknowledge_later():
        faulty.drop_next_reply()
        await board.backend.set_motor_state(1, 0.5)
        with caplog.at_level(logging.WARNING), safe_state_pass():
            await board.make_safe()
        assert [motor.value for motor in sim.motors] == [0, 0]  # braked
    assert any("MOT:1:SET:500" in record.getMessage() for record in caplog.records)
    await board.close()


async def test_the_safety_nets_synchronous_path_drops_what_is_owed(
    caplog: pytest.LogCaptureFixture,
) -> None:
    case, board, _, _ = await _connect("motor-fw4")
    backend = board.backend
    with acknowledge_later():
        await backend.set_motor_state(0, 0.5)
        with caplog.at_level(logging.WARNING):
            assert backend.make_safe_now(0.5)
        assert backend.link.acknowledgement_owed is None
        assert any("not checked" in record.getMessage() for record in caplog.records)
        # The replies still coming are resynchronised away before the next request.
        assert await case.ask(backend) == case.expected
    assert [motor.value for motor in case.sim.motors] == [0, 0]
    await board.close()


async def test_closing_at_once_drops_what_is_owed(caplog: pytest.LogCaptureFixture) -> None:
    _, board, _, _ = await _connect("servo-fw4")
    link = board.backend.link
    with acknowledge_later():
        await board.backend.set_servo_position(0, 0.5)
    with caplog.at_level(logging.WARNING):
        board.backend.close_now()
    assert link.acknowledgement_owed is None
    assert any("not checked" in record.getMessage() for record in caplog.records)
    board.backend.close_now()  # idempotent, and silent


@pytest.mark.parametrize("name", list(CASES))
async def test_a_dirty_link_waits_for_the_acknowledgement(name: str) -> None:
    case, board, faulty, _ = await _connect(name)
    backend = board.backend
    faulty.delay_next_reply(TIMEOUT + 0.02)
    with pytest.raises(CommunicationTimeoutError):
        await case.ask(backend)
    with acknowledge_later():
        await case.act(backend)  # the late reply may still come: this one waits
        assert backend.link.acknowledgement_owed is None
        assert case.remembered(backend)
    await board.close()


@pytest.mark.parametrize("name", ["motor-fw4", "sb2024"])
async def test_an_anyio_cancellation_while_confirming_finishes_the_confirmation(
    name: str,
) -> None:
    case, board, faulty, _ = await _connect(name)
    backend = board.backend
    with acknowledge_later():
        faulty.delay_next_reply(TIMEOUT / 2)
        await case.act(backend)
        with anyio.move_on_after(TIMEOUT / 10):
            await case.ask(backend)
        assert backend.link.acknowledgement_owed is None
        assert case.remembered(backend)
        assert await case.ask(backend) == case.expected
    await board.close()


@pytest.mark.parametrize("name", ["motor-fw4", "sb2024", "sb2019"])
async def test_a_native_cancellation_while_confirming_leaves_the_link_in_step(
    name: str,
) -> None:
    case, board, faulty, _ = await _connect(name)
    backend = board.backend
    with acknowledge_later():
        faulty.delay_next_reply(TIMEOUT / 2)
        await case.act(backend)
        task = asyncio.ensure_future(case.ask(backend))
        await asyncio.sleep(TIMEOUT / 10)
        task.cancel()
        with pytest.raises(asyncio.CancelledError):
            await task
        assert backend.link.acknowledgement_owed is None
        # The acknowledgement was left unread: the link knows, and is put back in step.
        assert await case.ask(backend) == case.expected
        assert await case.ask(backend) == case.expected
    await board.close()


async def test_a_caller_cancelled_before_it_writes_sends_nothing() -> None:
    case, board, _, recording = await _connect("motor-fw4")
    backend = board.backend
    with acknowledge_later(), anyio.CancelScope() as scope:
        scope.cancel()
        await case.act(backend)
    assert recording.sent == b""
    assert backend.link.acknowledgement_owed is None
    await board.close()


async def test_a_command_that_cannot_be_written_in_time_times_out() -> None:
    class Stuck(SimulatorStream):
        stuck = False

        async def send(self, data: bytes) -> None:
            if self.stuck:
                await anyio.sleep_forever()
            await super().send(data)

    sim = SRMotorBoardFw4Simulator("srM9")
    stream = Stuck(sim, time_scale=0)
    board = await QuickMotor.from_stream(stream, port="stuck", serial_number="srM9")
    backend = board.backend
    assert isinstance(backend, QuickMotor)
    stream.stuck = True
    with acknowledge_later(), pytest.raises(CommunicationTimeoutError, match="could not send"):
        await backend.set_motor_state(0, 0.5)
    assert backend.link.acknowledgement_owed is None
    assert backend.link.is_dirty
    assert backend.last_sent[0] is None
    stream.stuck = False
    await board.close()


async def test_a_port_gone_while_confirming_is_a_disconnection() -> None:
    case, board, faulty, _ = await _connect("motor-fw4")
    backend = board.backend
    with acknowledge_later():
        faulty.drop_next_reply()
        await case.act(backend)
        faulty.disconnect()
        with pytest.raises(BoardDisconnectionError, match="earlier command"):
            await case.ask(backend)
    assert not backend.is_connected
    await board.close()


@pytest.mark.parametrize("call", ["send", "read", "drain"])
async def test_every_way_to_the_link_confirms_first(call: str) -> None:
    case, board, faulty, _ = await _connect("motor-fw4")
    link: SerialLink = board.backend.link
    with acknowledge_later():
        faulty.corrupt_next_reply()
        await case.act(board.backend)
        with pytest.raises(EarlierCommandError):
            if call == "send":
                await link.send(b"*IDN?\n")
            elif call == "read":
                await link.read_line(timeout=TIMEOUT)
            else:
                await link.drain()
    assert link.acknowledgement_owed is None
    await board.close()


async def test_confirm_reads_what_is_owed_now() -> None:
    case, board, faulty, _ = await _connect("motor-fw4")
    link: SerialLink = board.backend.link
    await link.confirm()  # nothing owed: nothing happens
    with acknowledge_later():
        await case.act(board.backend)
        await link.confirm()
        assert link.acknowledgement_owed is None and case.remembered(board.backend)
        faulty.drop_next_reply()
        await case.act(board.backend)
        with pytest.raises(EarlierCommandError, match="MOT:0:SET:500"):
            await link.confirm()
    await board.close()


@pytest.mark.parametrize("style", ["anyio", "asyncio"])
@pytest.mark.parametrize("name", ["sb-arduino", "ruggeduino"])
async def test_random_cancellations_leave_no_wrong_answer_or_stale_cache(
    name: str, style: str
) -> None:
    with acknowledge_later():
        report = await cancellation_trials(name, style, 80, seed=11)  # type: ignore[arg-type]
    assert report.trials == 80
    assert (report.wrong_answers, report.mismatches, report.errors) == (0, 0, 0), report.details


async def test_stale_input_before_a_command_is_discarded() -> None:
    case, board, _, _ = await _connect("motor-fw4")
    link: SerialLink = board.backend.link
    with acknowledge_later():
        link._buffer += b"left over by a read\n"
        await case.act(board.backend)
        assert link.buffered == b""
        assert await case.ask(board.backend) == case.expected
    await board.close()


async def test_a_drain_after_a_good_acknowledgement_drains() -> None:
    case, board, _, _ = await _connect("motor-fw4")
    link: SerialLink = board.backend.link
    with acknowledge_later():
        await case.act(board.backend)
        assert await link.drain(0.005) == 0
    assert link.acknowledgement_owed is None and case.remembered(board.backend)
    await board.close()


async def test_waiting_for_an_acknowledgement_that_never_comes_times_out() -> None:
    # Outside acknowledge_later(), each generation's own timeout message is kept.
    _, board, faulty, _ = await _connect("sb2024")
    faulty.drop_next_reply()
    with pytest.raises(CommunicationTimeoutError, match="did not answer"):
        await board.backend.write_gpio_pin_digital_state(4, True)
    await board.close()
    _, board, faulty, _ = await _connect("motor-fw4")
    faulty.drop_next_reply()
    with pytest.raises(CommunicationTimeoutError, match="12 V"):
        await board.backend.set_motor_state(0, 0.5)
    faulty.drop_next_reply()
    with pytest.raises(CommunicationTimeoutError, match="12 V"):
        await board.backend._query_then(b"*STATUS?\n", bytes)
    await board.close()


async def test_a_command_to_a_vanished_port_is_a_disconnection() -> None:
    case, board, faulty, _ = await _connect("motor-fw4")
    faulty.disconnect()
    with pytest.raises(BoardDisconnectionError):
        await case.act(board.backend)
    assert not board.backend.is_connected
    with pytest.raises(BoardDisconnectionError):
        await case.act(board.backend)  # lost (and given as a stream: not looked for)
    await board.close()


async def test_a_board_that_comes_back_owes_nothing_from_before() -> None:
    sim = SRMotorBoardFw4Simulator("srM1")
    ports = [usb_port("/dev/ttyUSB0", "srM1", 0x0403, 0x6001,
                      manufacturer="Student Robotics", product="MCV4B")]

    async def opener(port: str, baudrate: int) -> Any:
        return SimulatorStream(sim, time_scale=0)

    options = DiscoveryOptions(port_source=lambda: ports, opener=opener, time_scale=0.01)
    (board,) = await SRV4MotorBoardFw4HardwareBackend.discover(options=options)
    backend = board.backend
    assert isinstance(backend, SRV4MotorBoardFw4HardwareBackend)
    backend.reconnect_policy = QUICK
    await board.setup()
    with acknowledge_later():
        await backend.set_motor_state(0, 0.5)
        assert backend.link.acknowledgement_owed is not None
        sim.unplug()
        with pytest.raises(BoardDisconnectionError, match="earlier command"):
            await backend.get_motor_state(1)
        assert not backend.is_connected
        sim.plug()
        await backend.set_motor_state(1, 0.25)  # found again, on a new link
        assert backend.reconnections == 1
        assert backend.last_sent == [None, None]  # forgotten; 0.25 not confirmed yet
        assert await backend.get_motor_state(1) == 0.25
    assert backend.last_sent == [None, 0.25]
    assert sim.motors[1].value == 250
    await board.close()


def test_a_loop_run_in_the_callers_thread_takes_the_switch_from_its_context() -> None:
    # How a sync facade turns it on: the task run_until_complete makes copies the
    # caller's context, so the switch set around the call holds inside it.
    loop = asyncio.new_event_loop()
    try:
        board = loop.run_until_complete(
            QuickMotor.from_stream(
                SimulatorStream(SRMotorBoardFw4Simulator("srM5"), time_scale=0),
                port="sim", serial_number="srM5",
            )
        )
        backend = board.backend
        assert isinstance(backend, QuickMotor)
        with acknowledge_later():
            loop.run_until_complete(backend.set_motor_state(0, 0.5))
        assert backend.link.acknowledgement_owed == b"MOT:0:SET:500\n"
        loop.run_until_complete(backend.set_motor_state(1, 0.5))  # switch off: waits
        assert backend.link.acknowledgement_owed is None
        assert backend.last_sent == [0.5, 0.5]
        loop.run_until_complete(board.close())
    finally:
        loop.close()


async def test_a_call_that_only_reads_what_the_backend_remembers_confirms_first() -> None:
    # get_motor_state answers from what the backend remembers: the owed acknowledgement is
    # read first, so the answer is the command just sent, never the one before it.
    _, board, _, _ = await _connect("motor-fw4")
    backend = board.backend
    with acknowledge_later():
        await backend.set_motor_state(1, MotorSpecialState.BRAKE)
        assert backend.owes_acknowledgement()
        assert await backend.get_motor_state(1) is MotorSpecialState.BRAKE
        assert not backend.owes_acknowledgement()
    await board.close()


async def test_a_failure_found_by_a_remembering_call_is_raised_by_it() -> None:
    case, board, _, _ = await _connect("motor-fw4")
    backend = board.backend
    with acknowledge_later():
        await backend._act(case.refused)
        with pytest.raises(EarlierCommandError, match="earlier command"):
            await backend.get_motor_state(0)
        assert not backend.owes_acknowledgement()
    await board.close()


@pytest.mark.parametrize("name", ["sr-arduino-fw2", "sb2024", "ruggeduino-fw1", "sb2019"])
async def test_a_pin_mode_change_waits_for_its_acknowledgement(name: str) -> None:
    # The mode a pin is remembered in is what its other calls check (a write to an input
    # is refused before anything is sent), so it is the board's, even with the switch on.
    _, board, _, _ = await _connect(name)
    backend = board.backend
    with acknowledge_later():
        await backend.set_gpio_pin_mode(7, GPIOPinMode.DIGITAL_OUTPUT)
        assert not backend.owes_acknowledgement()
        assert await backend.get_gpio_pin_mode(7) is GPIOPinMode.DIGITAL_OUTPUT
    await board.close()


def test_a_backend_with_no_link_owes_nothing() -> None:
    # The base class's answer, which console and simulated-in-memory backends keep.
    from j5aio.backends.backend import Backend

    assert Backend.owes_acknowledgement(None) is False  # type: ignore[arg-type]
    anyio.run(Backend.confirm_acknowledgement, None)  # type: ignore[arg-type]

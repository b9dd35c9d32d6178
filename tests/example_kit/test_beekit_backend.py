"""The Bee Board's backend against a scripted board, injected faults and a serial port."""

from __future__ import annotations

import pytest
from beekit.backend import BeeBackend
from beekit.boards import BeeBoard
from beekit.simulator import BeeSimulator

from j5aio.backends.hardware.transports import ByteStream, SimulatorStream
from j5aio.components.motor import MotorSpecialState
from j5aio.errors import (
    BoardDisconnectionError,
    CommunicationTimeoutError,
    NotSupportedByHardwareError,
    UnexpectedReplyError,
    UnsupportedFirmwareError,
)
from j5aio.testing import RecordingStream, ScriptedStream
from j5aio.testing.plugin import FaultyStreamFactory, PtySimulatorFactory

HANDSHAKE = (b"?\n", b"BEE:2.1\n")
SETUP = [(b"M0 0\n", b"OK\n"), (b"M1 0\n", b"OK\n"), (b"L0\n", b"OK\n")]


async def test_a_power_is_sent_as_rounded_steps() -> None:
    stream = ScriptedStream([HANDSHAKE, *SETUP, (b"M1 -67\n", b"OK\n"), (b"L1\n", b"OK\n")])
    board = await BeeBackend.from_stream(stream, port="script", serial_number="B1")
    assert board.firmware_version == "2.1"  # typed as BeeBoard: no isinstance needed
    await board.setup()
    await board.motors[1].set_power(-0.667)
    assert await board.motors[1].get_power() == -0.67
    await board.led.set_state(True)
    stream.assert_all_used()
    await board.close()


async def test_brake_is_refused_and_nothing_is_sent() -> None:
    stream = ScriptedStream([HANDSHAKE])
    board = await BeeBackend.from_stream(stream, port="script", serial_number="B1")
    with pytest.raises(NotSupportedByHardwareError, match="cannot BRAKE"):
        await board.motors[0].set_power(MotorSpecialState.BRAKE)
    stream.assert_all_used()
    await board.close()


async def test_an_old_firmware_or_a_stranger_is_refused() -> None:
    with pytest.raises(UnsupportedFirmwareError, match=r"1\.4"):
        await BeeBackend.from_stream(
            ScriptedStream([(b"?\n", b"BEE:1.4\n")]), port="script", serial_number="B1",
        )
    with pytest.raises(UnexpectedReplyError, match="not a Bee Board"):
        await BeeBackend.from_stream(
            ScriptedStream([(b"?\n", b"WASP:2\n")]), port="script", serial_number="B1",
        )


async def test_a_refusal_and_a_wrong_reply_are_communication_errors() -> None:
    stream = ScriptedStream([HANDSHAKE, (b"B\n", b"ERR busy\n"), (b"L1\n", b"??\n")])
    board = await BeeBackend.from_stream(stream, port="script", serial_number="B1")
    with pytest.raises(UnexpectedReplyError, match="refused b'B': ERR busy"):
        await board.button.get_is_pressed()
    with pytest.raises(UnexpectedReplyError, match="expected OK after b'L1'"):
        await board.led.set_state(True)
    await board.close()


async def connect(stream: ByteStream) -> BeeBoard:
    board = await BeeBackend.from_stream(stream, port="sim", serial_number="B1", time_scale=0)
    await board.setup()
    return board


async def test_faults_surface_as_the_right_errors(
    j5aio_faulty_stream: FaultyStreamFactory,
) -> None:
    simulator = BeeSimulator()
    stream = j5aio_faulty_stream(SimulatorStream(simulator, time_scale=0))
    board = await connect(stream)
    stream.corrupt_next_reply()
    with pytest.raises(UnexpectedReplyError):
        await board.button.get_is_pressed()
    stream.drop_next_reply()
    with pytest.raises(CommunicationTimeoutError):
        await board.led.set_state(True)
    simulator.button_held = True
    assert await board.button.get_is_pressed() is True  # the link recovered
    stream.disconnect()
    with pytest.raises(BoardDisconnectionError):
        await board.motors[0].set_power(0.5)
    await board.close()


async def test_the_board_on_a_serial_port(j5aio_pty_simulator: PtySimulatorFactory) -> None:
    simulator = BeeSimulator()
    board = await BeeBackend.attach(j5aio_pty_simulator(simulator), time_scale=0)
    await board.setup()
    await board.motors[0].set_power(0.333)
    await board.led.set_state(True)
    await board.close()
    assert simulator.motor_steps == [33, 0]
    assert simulator.led is True


def test_the_simulator_answers_what_it_does_not_know_with_err() -> None:
    simulator = BeeSimulator()
    assert simulator.receive(b"M0 1") == b""  # half a line: nothing yet
    assert simulator.receive(b"01\nM2 0\nM0 x\nL1\n") == (
        b"ERR steps out of range 101\nERR unknown command M2 0\nERR bad steps x\nOK\n"
    )
    assert simulator.motor_steps == [0, 0]
    assert simulator.led is True
    assert simulator.reset() == b""
    assert simulator.led is False


async def test_send_writes_a_command_that_has_no_reply() -> None:
    simulator = BeeSimulator()
    stream = RecordingStream(SimulatorStream(simulator, time_scale=0))
    board = await BeeBackend.from_stream(stream, port="sim", serial_number="B1", time_scale=0)
    backend = board.backend
    assert isinstance(backend, BeeBackend)
    stream.clear()
    await backend.send(b"L1\n")  # the board answers OK, which nobody reads here
    assert stream.sent == b"L1\n"
    assert simulator.led is True
    backend.firmware_version = "2.9"
    assert board.firmware_version == "2.9"
    await board.close()

"""The worked example of docs/testing-backends.rst: testing the Blinkenboard's backend.

The document includes this file piece by piece, so every step it shows is run here.
"""

from __future__ import annotations

import sys
from pathlib import Path

import anyio
import pytest

from j5aio.backends.hardware.transports import ByteStream, SimulatorStream
from j5aio.errors import (
    BoardDisconnectionError,
    CommunicationTimeoutError,
    UnexpectedReplyError,
    UnsupportedFirmwareError,
)
from j5aio.testing import RecordingStream, ScriptedStream
from j5aio.testing.conformance import (
    ButtonInterfaceConformance,
    ButtonSubject,
    LEDInterfaceConformance,
    LEDSubject,
)
from j5aio.testing.plugin import FaultyStreamFactory, PtySimulatorFactory

# The example lives in examples/backend_author, beside (not inside) the j5aio package.
sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from examples.backend_author.blinken_backend import BlinkenBoardBackend
from examples.backend_author.blinken_simulator import BlinkenSimulator
from examples.backend_author.blinkenboard import BlinkenBoard

# [step 1: scripted]
HANDSHAKE = (b"?\n", b"BLINKEN:1.2\n")
SETUP = [(b"L%d0\n" % led, b"OK\n") for led in range(4)]


async def test_lighting_an_led_sends_one_line() -> None:
    stream = ScriptedStream([HANDSHAKE, *SETUP, (b"L21\n", b"OK\n")])
    board = await BlinkenBoardBackend.from_stream(stream, port="script", serial_number="B1")
    assert isinstance(board, BlinkenBoard)
    await board.setup()
    await board.leds[2].set_state(True)
    assert await board.leds[2].get_state() is True
    stream.assert_all_used()
    await board.close()


async def test_an_old_firmware_is_refused() -> None:
    stream = ScriptedStream([(b"?\n", b"BLINKEN:0.9\n")])
    with pytest.raises(UnsupportedFirmwareError, match=r"0\.9"):
        await BlinkenBoardBackend.from_stream(stream, port="script", serial_number="B1")
# [end step 1]


# [step 2: faults]
async def connect(stream: ByteStream) -> BlinkenBoard:
    board = await BlinkenBoardBackend.from_stream(
        stream, port="sim", serial_number="B1", time_scale=0,
    )
    assert isinstance(board, BlinkenBoard)
    await board.setup()
    return board


async def test_a_corrupted_reply_is_a_communication_error(
    j5aio_faulty_stream: FaultyStreamFactory,
) -> None:
    stream = j5aio_faulty_stream(SimulatorStream(BlinkenSimulator(), time_scale=0))
    board = await connect(stream)
    stream.corrupt_next_reply()
    with pytest.raises(UnexpectedReplyError):
        await board.button.get_is_pressed()
    assert await board.button.get_is_pressed() is False  # the next exchange is clean
    await board.close()


async def test_a_lost_reply_times_out_and_the_link_recovers(
    j5aio_faulty_stream: FaultyStreamFactory,
) -> None:
    simulator = BlinkenSimulator()
    stream = j5aio_faulty_stream(SimulatorStream(simulator, time_scale=0))
    board = await connect(stream)
    stream.drop_next_reply()
    with pytest.raises(CommunicationTimeoutError):
        await board.leds[0].set_state(True)
    simulator.button_held = True
    assert await board.button.get_is_pressed() is True
    await board.close()


async def test_an_unplugged_board_is_a_disconnection(
    j5aio_faulty_stream: FaultyStreamFactory,
) -> None:
    stream = j5aio_faulty_stream(SimulatorStream(BlinkenSimulator(), time_scale=0))
    board = await connect(stream)
    stream.disconnect()
    with pytest.raises(BoardDisconnectionError):
        await board.leds[1].set_state(True)
    await board.close()
# [end step 2]


# [step 3: conformance]
class BlinkenSuite:
    """Connects a backend to a fresh simulator, recording what it sends."""

    simulator: BlinkenSimulator
    stream: RecordingStream

    async def connect(self) -> BlinkenBoardBackend:
        self.simulator = BlinkenSimulator()
        self.stream = RecordingStream(SimulatorStream(self.simulator, time_scale=0))
        board = await connect(self.stream)
        self.stream.clear()
        assert isinstance(board.backend, BlinkenBoardBackend)
        return board.backend


class TestBlinkenLEDs(BlinkenSuite, LEDInterfaceConformance):
    async def make_backend(self) -> LEDSubject:
        backend = await self.connect()

        async def observe(identifier: int) -> bool:
            return bool(self.simulator.leds[identifier])

        return LEDSubject(
            backend=backend, identifiers=range(4), observe=observe,
            traffic=lambda: self.stream.sent,
        )


class TestBlinkenButton(BlinkenSuite, ButtonInterfaceConformance):
    async def make_backend(self) -> ButtonSubject:
        backend = await self.connect()

        async def set_pressed(identifier: int, pressed: bool) -> None:
            self.simulator.button_held = pressed

        async def press(identifier: int) -> None:
            self.simulator.button_held = True
            await anyio.sleep(backend.BUTTON_POLL_INTERVAL * 3)
            self.simulator.button_held = False

        return ButtonSubject(
            backend=backend, identifiers=[0], set_pressed=set_pressed, press=press,
            traffic=lambda: self.stream.sent,
        )
# [end step 3]


# [step 4: pty]
async def test_the_board_on_a_serial_port(j5aio_pty_simulator: PtySimulatorFactory) -> None:
    simulator = BlinkenSimulator()
    path = j5aio_pty_simulator(simulator)
    board = await BlinkenBoardBackend.attach(path, time_scale=0)
    assert isinstance(board, BlinkenBoard)
    assert board.firmware_version == "1.2"
    await board.setup()
    await board.leds[3].set_state(True)
    await board.close()
    assert simulator.leds == [False, False, False, True]
# [end step 4]


def test_the_simulator_refuses_what_it_does_not_know() -> None:
    simulator = BlinkenSimulator()
    assert simulator.open() == b""
    assert simulator.receive(b"L9") == b""
    assert simulator.receive(b"1\nB") == b"ERR unknown command L91\n"
    assert simulator.receive(b"\n") == b"B0\n"
    assert simulator.commands == [b"L91", b"B"]


async def test_the_backend_reports_a_refusal_and_a_stranger() -> None:
    stream = ScriptedStream([HANDSHAKE, (b"B\n", b"ERR busy\n"), (b"L01\n", b"??\n")])
    board = await BlinkenBoardBackend.from_stream(stream, port="script", serial_number="B1")
    assert isinstance(board, BlinkenBoard)
    with pytest.raises(UnexpectedReplyError, match="refused b'B': ERR busy"):
        await board.button.get_is_pressed()
    with pytest.raises(UnexpectedReplyError, match="expected OK after setting LED 0"):
        await board.leds[0].set_state(True)
    await board.close()
    stranger = ScriptedStream([(b"?\n", b"TOASTER:1\n")])
    with pytest.raises(UnexpectedReplyError, match="not a Blinkenboard"):
        await BlinkenBoardBackend.from_stream(stranger, port="script", serial_number="B1")


async def test_the_safe_state_is_sent_synchronously() -> None:
    simulator = BlinkenSimulator()
    stream = SimulatorStream(simulator, name="sim", time_scale=0)
    board = await BlinkenBoardBackend.from_stream(stream, port="sim", serial_number="B1")
    assert isinstance(board, BlinkenBoard)
    await board.setup()
    await board.leds[1].set_state(True)
    assert simulator.leds[1]
    assert board.backend.make_safe_now(0.5) is True
    assert simulator.leds == [False] * 4
    assert await board.leds[1].get_state() is False
    await board.leds[3].set_state(True)  # the link drained the replies it skipped
    assert simulator.leds == [False, False, False, True]
    await board.close()
    assert board.backend.make_safe_now(0.5) is False

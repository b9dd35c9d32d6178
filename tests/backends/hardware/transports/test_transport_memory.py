"""Tests of the in-memory streams, the simulator stream and the receive inbox."""

from __future__ import annotations

import time

import anyio
import anyio.lowlevel
import pytest

from j5aio.backends.hardware.transports import (
    ByteStream,
    SerialLink,
    SerialSimulatorLike,
    SimulatorStream,
    memory_stream_pair,
    read_line,
)
from j5aio.backends.hardware.transports._inbox import Inbox, fresh_copy
from j5aio.errors import BoardDisconnectionError, CommunicationError


class EchoSimulator:
    """A stand-in board simulator: boots with a banner, answers ``x`` with ``X``."""

    def __init__(
        self, *, banner: bytes = b"# Booted\n", boot_delay: float = 0.0, baudrate: int = 115200
    ) -> None:
        self.baudrate = baudrate
        self.boot_delay = boot_delay
        self.banner = banner
        self.opened = 0
        self.received: list[bytes] = []
        self._connected = True

    @property
    def connected(self) -> bool:
        return self._connected

    def unplug(self) -> None:
        self._connected = False

    def open(self) -> bytes:
        self.opened += 1
        return self.banner

    def receive(self, data: bytes) -> bytes:
        self.received.append(data)
        return data.upper()


# -- memory pair -------------------------------------------------------------------------


async def test_pair_delivers_bytes_both_ways() -> None:
    a, b = memory_stream_pair("host", "board")
    await a.send(b"hello")
    assert await b.receive() == b"hello"
    await b.send(b"world")
    assert await a.receive() == b"world"
    assert (a.name, b.name) == ("host", "board")
    assert isinstance(a, ByteStream)


async def test_receive_returns_at_most_max_bytes_and_keeps_the_rest() -> None:
    a, b = memory_stream_pair()
    await a.send(b"abcdef")
    assert await b.receive(4) == b"abcd"
    assert await b.receive(4) == b"ef"


async def test_receive_waits_for_data() -> None:
    a, b = memory_stream_pair()
    received: list[bytes] = []

    async def receive() -> None:
        received.append(await b.receive())

    async with anyio.create_task_group() as tg:
        tg.start_soon(receive)
        for _ in range(5):
            await anyio.lowlevel.checkpoint()
        assert received == []  # nothing sent yet: still waiting
        await a.send(b"x")
    assert received == [b"x"]


async def test_receive_rejects_a_max_bytes_below_one() -> None:
    a, _ = memory_stream_pair()
    with pytest.raises(ValueError, match="max_bytes"):
        await a.receive(0)


async def test_closing_one_end_gives_the_other_what_was_sent_then_eof() -> None:
    a, b = memory_stream_pair()
    await a.send(b"last words")
    await a.aclose()
    assert a.is_closed and not b.is_closed
    assert await b.receive() == b"last words"
    with pytest.raises(BoardDisconnectionError, match="other end has gone"):
        await b.receive()
    with pytest.raises(BoardDisconnectionError, match="other end has gone"):
        await b.send(b"anyone?")


async def test_a_closed_end_refuses_to_send_and_receive() -> None:
    a, b = memory_stream_pair()
    await b.send(b"unread")
    a.close_now()
    a.close_now()  # idempotent
    with pytest.raises(BoardDisconnectionError, match="closed"):
        await a.send(b"x")
    with pytest.raises(BoardDisconnectionError, match="closed"):
        await a.receive()
    assert "closed" in repr(a)


async def test_close_now_wakes_a_waiting_receive() -> None:
    a, _ = memory_stream_pair()
    with anyio.fail_after(1):
        async with anyio.create_task_group() as tg:

            async def close_soon() -> None:
                await anyio.sleep(0.01)
                a.close_now()

            tg.start_soon(close_soon)
            with pytest.raises(BoardDisconnectionError):
                await a.receive()


async def test_async_context_manager_closes() -> None:
    a, _ = memory_stream_pair()
    async with a as stream:
        assert stream is a
        assert "open" in repr(a)
    assert a.is_closed


async def test_a_cancelled_receive_loses_nothing() -> None:
    a, b = memory_stream_pair()
    with anyio.move_on_after(0.01):
        await b.receive()
    await a.send(b"kept")
    assert await b.receive() == b"kept"


# -- inbox -------------------------------------------------------------------------------


async def test_inbox_ignores_bytes_after_it_has_ended() -> None:
    inbox = Inbox()
    inbox.feed(b"ab")
    inbox.finish(CommunicationError("done"))
    inbox.feed(b"ignored")
    inbox.finish(CommunicationError("second reason is ignored"))
    assert inbox.ended
    assert len(inbox) == 2
    assert await inbox.take(10) == b"ab"
    with pytest.raises(CommunicationError, match="done"):
        await inbox.take(10)


async def test_inbox_take_by_returns_what_came_or_none_at_the_deadline() -> None:
    inbox = Inbox()
    now = anyio.current_time()
    assert await inbox.take_by(10, now + 0.01) is None
    assert anyio.current_time() >= now + 0.01
    inbox.feed(b"abc")
    assert await inbox.take_by(2, now) == b"ab"  # already there: no wait, whatever the time
    assert await inbox.take_by(2, now) == b"c"
    with pytest.raises(ValueError, match="at least 1"):
        await inbox.take_by(0, now)


async def test_inbox_take_by_wakes_for_bytes_and_for_the_end() -> None:
    inbox = Inbox()
    deadline = anyio.current_time() + 5
    async with anyio.create_task_group() as tg:

        async def feed_soon() -> None:
            await anyio.sleep(0.01)
            inbox.feed(b"hi")

        tg.start_soon(feed_soon)
        with anyio.fail_after(1):
            assert await inbox.take_by(10, deadline) == b"hi"

        async def end_soon() -> None:
            await anyio.sleep(0.01)
            inbox.finish(CommunicationError("ended"))

        tg.start_soon(end_soon)
        with anyio.fail_after(1), pytest.raises(CommunicationError, match="ended"):
            await inbox.take_by(10, deadline)


async def test_inbox_take_by_keeps_time_with_the_timer_of_an_earlier_wait() -> None:
    inbox = Inbox()
    start = anyio.current_time()
    inbox.feed(b"a")
    assert await inbox.take_by(10, start + 0.02) == b"a"  # no wait, no timer
    # A wait that ends with bytes leaves its timer (due at +0.02) for the next wait.
    async with anyio.create_task_group() as tg:

        async def feed_soon() -> None:
            await anyio.sleep(0.005)
            inbox.feed(b"b")

        tg.start_soon(feed_soon)
        assert await inbox.take_by(10, start + 0.02) == b"b"
    # A later deadline: the timer, due earlier, is set again, and the wait lasts.
    assert await inbox.take_by(10, start + 0.06) is None
    assert anyio.current_time() >= start + 0.06
    # An earlier deadline than the timer's: it is set earlier.
    long_wait = anyio.current_time()
    async with anyio.create_task_group() as tg:

        async def feed_late() -> None:
            await anyio.sleep(0.005)
            inbox.feed(b"c")

        tg.start_soon(feed_late)
        assert await inbox.take_by(10, long_wait + 5) == b"c"
    short_wait = anyio.current_time()
    with anyio.fail_after(1):
        assert await inbox.take_by(10, short_wait + 0.01) is None


async def test_inbox_timer_of_a_wait_by_a_deadline_leaves_a_plain_take_waiting() -> None:
    inbox = Inbox()
    async with anyio.create_task_group() as tg:

        async def feed(data: bytes, after: float) -> None:
            await anyio.sleep(after)
            inbox.feed(data)

        tg.start_soon(feed, b"w", 0.001)
        assert await inbox.take_by(10, anyio.current_time() + 0.01) == b"w"  # timer left
        tg.start_soon(feed, b"x", 0.03)
        with anyio.fail_after(1):
            assert await inbox.take(10) == b"x"  # the timer lapsed meanwhile; take waited on


async def test_inbox_take_by_cancelled_loses_nothing() -> None:
    inbox = Inbox()
    with anyio.move_on_after(0.01):
        await inbox.take_by(10, anyio.current_time() + 5)
    inbox.feed(b"kept")
    assert await inbox.take_by(10, anyio.current_time() + 5) == b"kept"


async def test_receive_by_of_a_stream_with_a_receive_of_its_own_uses_it() -> None:
    class Slow(SimulatorStream):
        receives = 0

        async def receive(self, max_bytes: int = 4096) -> bytes:
            self.receives += 1
            return await super().receive(max_bytes)

    stream = Slow(EchoSimulator(banner=b""))
    assert await stream.receive_by(anyio.current_time() + 0.01) is None  # the default
    await stream.send(b"ping\n")
    assert await stream.receive_by(anyio.current_time() + 1) == b"PING\n"
    assert stream.receives == 2
    a, b = memory_stream_pair()
    a.send_nowait(b"x")
    assert await b.receive_by(anyio.current_time() + 1) == b"x"


def test_fresh_copy_keeps_the_cause() -> None:
    cause = OSError("underneath")
    error = BoardDisconnectionError("gone")
    error.__cause__ = cause
    again = fresh_copy(error)
    assert again is not error
    assert type(again) is BoardDisconnectionError
    assert again.args == error.args
    assert again.__cause__ is cause


# -- simulator stream --------------------------------------------------------------------


def test_echo_simulator_has_the_simulator_shape() -> None:
    assert isinstance(EchoSimulator(), SerialSimulatorLike)


async def test_simulator_stream_opens_the_simulator_and_emits_its_banner() -> None:
    simulator = EchoSimulator()
    stream = SimulatorStream(simulator)
    assert simulator.opened == 1
    assert stream.simulator is simulator
    assert stream.name == "simulated EchoSimulator"
    assert await stream.receive() == b"# Booted\n"


async def test_simulator_stream_passes_requests_and_queues_responses() -> None:
    simulator = EchoSimulator(banner=b"")
    stream = SimulatorStream(simulator, name="sim")
    await stream.send(b"ping\n")
    assert simulator.received == [b"ping\n"]
    assert await stream.receive(2) == b"PI"
    assert await stream.receive() == b"NG\n"
    assert stream.name == "sim"


async def test_simulator_stream_sends_at_once_without_waiting() -> None:
    simulator = EchoSimulator(banner=b"")
    stream = SimulatorStream(simulator, name="sim")
    assert stream.send_nowait(b"ping\n") is True
    assert simulator.received == [b"ping\n"]
    assert await stream.receive() == b"PING\n"
    stream.close_now()
    with pytest.raises(BoardDisconnectionError):
        stream.send_nowait(b"ping\n")


async def test_a_stream_with_a_send_of_its_own_never_sends_round_it() -> None:
    class Counting(SimulatorStream):
        sends = 0

        async def send(self, data: bytes) -> None:
            self.sends += 1
            await super().send(data)

    simulator = EchoSimulator(banner=b"")
    stream = Counting(simulator)
    assert stream.send_nowait(b"ping\n") is False  # the default: nothing sent
    assert simulator.received == []
    link = SerialLink(stream)
    assert await link.exchange(b"ping\n", read_line()) == b"PING"
    assert stream.sends == 1
    assert simulator.received == [b"ping\n"]


async def test_memory_streams_send_at_once_without_waiting() -> None:
    ours, theirs = memory_stream_pair()
    assert ours.send_nowait(b"x") is True
    await ours.send(b"y")
    assert await theirs.receive() == b"xy"
    theirs.close_now()
    with pytest.raises(BoardDisconnectionError):
        ours.send_nowait(b"z")


async def test_boot_output_appears_after_the_scaled_boot_delay() -> None:
    simulator = EchoSimulator(boot_delay=2.0)
    stream = SimulatorStream(simulator, time_scale=0.02)  # 40 ms
    await stream.send(b"early\n")  # answered only after the banner, as on a wire
    start = time.monotonic()
    assert await stream.receive() == b"# Booted\nEARLY\n"
    assert time.monotonic() - start >= 0.03


async def test_time_scale_zero_makes_the_boot_instant() -> None:
    stream = SimulatorStream(EchoSimulator(boot_delay=5.0), time_scale=0)
    with anyio.fail_after(0.5):
        assert await stream.receive() == b"# Booted\n"


async def test_uart_timing_delays_by_the_time_on_the_wire() -> None:
    simulator = EchoSimulator(banner=b"", baudrate=10_000)  # 1 ms a byte
    stream = SimulatorStream(simulator, uart_timing=True)
    start = time.monotonic()
    await stream.send(b"0123456789")
    assert await stream.receive() == b"0123456789"
    assert time.monotonic() - start >= 0.018  # 10 bytes there and 10 back


async def test_a_disconnected_simulator_raises_on_send_and_receive() -> None:
    simulator = EchoSimulator(banner=b"")
    stream = SimulatorStream(simulator)
    simulator.unplug()
    with pytest.raises(BoardDisconnectionError, match="disconnected"):
        await stream.send(b"x")
    with pytest.raises(BoardDisconnectionError, match="disconnected"):
        await stream.receive()


async def test_unplugging_wakes_a_waiting_receive_promptly() -> None:
    simulator = EchoSimulator(banner=b"")
    stream = SimulatorStream(simulator, poll_interval=0.005)
    with anyio.fail_after(1):
        async with anyio.create_task_group() as tg:

            async def unplug_soon() -> None:
                await anyio.sleep(0.02)
                simulator.unplug()

            tg.start_soon(unplug_soon)
            with pytest.raises(BoardDisconnectionError):
                await stream.receive()


async def test_closing_a_simulator_stream_wakes_a_waiting_receive() -> None:
    stream = SimulatorStream(EchoSimulator(banner=b""))
    with anyio.fail_after(1):
        async with anyio.create_task_group() as tg:

            async def close_soon() -> None:
                await anyio.sleep(0.01)
                await stream.aclose()

            tg.start_soon(close_soon)
            with pytest.raises(BoardDisconnectionError, match="closed"):
                await stream.receive()
    assert stream.is_closed
    with pytest.raises(BoardDisconnectionError, match="closed"):
        await stream.send(b"x")


async def test_simulator_stream_validates_its_arguments() -> None:
    with pytest.raises(ValueError, match="time_scale"):
        SimulatorStream(EchoSimulator(), time_scale=-1)
    with pytest.raises(ValueError, match="max_bytes"):
        await SimulatorStream(EchoSimulator()).receive(0)


async def test_a_simulator_stream_sends_synchronously() -> None:
    simulator = EchoSimulator(banner=b"")
    stream = SimulatorStream(simulator, time_scale=0)
    stream.send_now(b"brake", 0.1)
    assert simulator.received == [b"brake"]
    assert await stream.receive() == b"BRAKE"
    stream.close_now()
    with pytest.raises(BoardDisconnectionError, match="closed"):
        stream.send_now(b"x", 0.1)


async def test_simulator_stream_receive_by_takes_a_due_reply_after_a_checkpoint() -> None:
    stream = SimulatorStream(EchoSimulator(banner=b""), time_scale=0)
    stream.send_nowait(b"ping\n")
    with anyio.CancelScope() as scope:
        scope.cancel()  # a checkpoint comes first: a cancelled caller takes nothing
        await stream.receive_by(anyio.current_time() + 1)
    assert await stream.receive_by(anyio.current_time() + 1, 2) == b"PI"
    assert await stream.receive_by(anyio.current_time() + 1) == b"NG\n"


async def test_simulator_stream_receive_by_waits_for_output_not_yet_due() -> None:
    simulator = EchoSimulator(banner=b"", baudrate=10_000)  # 1 ms a byte
    stream = SimulatorStream(simulator, uart_timing=True)
    stream.send_nowait(b"0123456789")
    assert await stream.receive_by(anyio.current_time() + 0.001) is None  # not yet
    assert await stream.receive_by(anyio.current_time() + 5) == b"0123456789"


async def test_simulator_stream_receive_by_says_none_once_its_deadline_has_passed() -> None:
    stream = SimulatorStream(EchoSimulator(banner=b""), time_scale=0)
    stream.send_nowait(b"late\n")
    assert await stream.receive_by(anyio.current_time() - 1) is None  # as the default says
    assert await stream.receive_by(anyio.current_time() + 1) == b"LATE\n"  # still there
    assert await stream.receive_by(anyio.current_time() + 0.01) is None  # nothing more


async def test_simulator_stream_receive_by_refuses_bad_sizes_and_dead_boards() -> None:
    simulator = EchoSimulator(banner=b"")
    stream = SimulatorStream(simulator)
    with pytest.raises(ValueError, match="max_bytes"):
        await stream.receive_by(anyio.current_time() + 1, 0)
    simulator.unplug()
    with pytest.raises(BoardDisconnectionError, match="disconnected"):
        await stream.receive_by(anyio.current_time() + 1)

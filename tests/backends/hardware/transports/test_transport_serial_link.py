"""Tests of SerialLink: serialised, shielded exchanges with timeouts and dirty draining."""

from __future__ import annotations

import asyncio
import logging
import random
from collections.abc import AsyncIterator, Callable
from dataclasses import dataclass, field
from typing import Any

import anyio
import anyio.abc
import anyio.lowlevel
import pytest

from j5aio.backends.acknowledgements import acknowledge_later
from j5aio.backends.hardware.transports import (
    TRACE,
    ByteStream,
    MemoryStream,
    SerialLink,
    line_starts_with,
    memory_stream_pair,
    read_exactly,
    read_line,
    read_lines_until,
)
from j5aio.backends.hardware.transports.readers import ReplyReader, matching
from j5aio.errors import (
    BoardDisconnectionError,
    CommunicationError,
    CommunicationTimeoutError,
    UnexpectedReplyError,
)
from j5aio.testing.transports import FaultyStream, RecordingStream

Responder = Callable[[bytes], bytes | None]


@dataclass
class LinePeer:
    """A board on the far side of a memory pair that answers each line it receives."""

    stream: MemoryStream
    respond: Responder
    delay: Callable[[], float] = lambda: 0.0
    lines: list[bytes] = field(default_factory=list)

    async def run(self) -> None:
        buffer = bytearray()
        try:
            while True:
                buffer += await self.stream.receive()
                while b"\n" in buffer:
                    line, _, rest = bytes(buffer).partition(b"\n")
                    buffer = bytearray(rest)
                    self.lines.append(line)
                    reply = self.respond(line)
                    pause = self.delay()
                    if pause:
                        await anyio.sleep(pause)
                    if reply:
                        await self.stream.send(reply)
        except BoardDisconnectionError:
            pass


def upper(line: bytes) -> bytes:
    return line.upper() + b"\r\n"


@pytest.fixture
async def peer_pair() -> AsyncIterator[tuple[MemoryStream, MemoryStream]]:
    host, board = memory_stream_pair("host", "board")
    yield host, board
    host.close_now()
    board.close_now()


async def start_peer(
    tg: anyio.abc.TaskGroup, board: MemoryStream, respond: Responder = upper, **kwargs: object
) -> LinePeer:
    peer = LinePeer(board, respond, **kwargs)  # type: ignore[arg-type]
    tg.start_soon(peer.run)
    return peer


# -- the basics --------------------------------------------------------------------------


async def test_exchange_sends_and_returns_the_parsed_reply(
    peer_pair: tuple[MemoryStream, MemoryStream],
) -> None:
    host, board = peer_pair
    link = SerialLink(host)
    async with anyio.create_task_group() as tg:
        peer = await start_peer(tg, board)
        assert await link.exchange(b"v\n", read_line(), timeout=1) == b"V"
        assert peer.lines == [b"v"]
        tg.cancel_scope.cancel()
    assert link.name == "host" and link.stream is host
    assert not link.is_dirty and not link.is_closed
    assert repr(link) == "<SerialLink 'host' open>"


async def test_exchange_with_a_multi_line_reply() -> None:
    host, board = memory_stream_pair()
    link = SerialLink(host, name="arduino")

    def sb_arduino(line: bytes) -> bytes:
        return b"# " + line + b"\r\n> H\r\n+ OK\r\n"

    async with anyio.create_task_group() as tg:
        await start_peer(tg, board, sb_arduino)
        reply = await link.exchange(
            b"R 2\n", read_lines_until(line_starts_with(b"+", b"-")), timeout=1
        )
        assert reply == [b"# R 2", b"> H", b"+ OK"]
        tg.cancel_scope.cancel()


async def test_exchange_of_exact_bytes_and_an_empty_request() -> None:
    host, board = memory_stream_pair()
    link = SerialLink(host)
    await board.send(b"\x01\x02\x03")
    assert await link.exchange(b"", read_exactly(3), timeout=1) == b"\x01\x02\x03"


async def test_send_has_no_reply(peer_pair: tuple[MemoryStream, MemoryStream]) -> None:
    host, board = peer_pair
    link = SerialLink(host)
    await link.send(b"\x02\xfd")
    assert await board.receive() == b"\x02\xfd"


async def test_read_line_reads_a_banner_and_keeps_the_rest_for_the_next_read() -> None:
    host, board = memory_stream_pair()
    link = SerialLink(host)
    await board.send(b"# Booted\r\n# SBDuino GPIO v2019.8.0\r\n")
    assert await link.read_line(timeout=1) == b"# Booted"
    assert link.buffered == b"# SBDuino GPIO v2019.8.0\r\n"
    assert await link.read_line(timeout=1) == b"# SBDuino GPIO v2019.8.0"


async def test_read_times_out_without_marking_the_link_dirty() -> None:
    host, board = memory_stream_pair()
    link = SerialLink(host)
    await board.send(b"half a li")
    with pytest.raises(CommunicationTimeoutError, match="half a li"):
        await link.read_line(timeout=0.02)
    assert not link.is_dirty
    await board.send(b"ne\n")
    assert await link.read_line(timeout=1) == b"half a line"


async def test_read_reports_unparseable_input() -> None:
    host, board = memory_stream_pair()
    link = SerialLink(host)
    await board.send(b"x" * 100)
    with pytest.raises(UnexpectedReplyError, match="memory-a: bad reply: received 100 bytes"):
        await link.read(read_line(max_length=10), timeout=1)


async def test_stale_input_is_never_taken_as_a_reply(
    peer_pair: tuple[MemoryStream, MemoryStream],
) -> None:
    host, board = peer_pair
    link = SerialLink(host)
    async with anyio.create_task_group() as tg:
        await board.send(b"banner one\nbanner two\n")
        assert await link.read_line(timeout=1) == b"banner one"
        await start_peer(tg, board)
        assert await link.exchange(b"q\n", read_line(), timeout=1) == b"Q"
        tg.cancel_scope.cancel()


async def test_bytes_after_a_reply_make_the_link_dirty(
    peer_pair: tuple[MemoryStream, MemoryStream],
) -> None:
    host, board = peer_pair
    link = SerialLink(host, quiet_time=0.01)
    async with anyio.create_task_group() as tg:
        await start_peer(tg, board, lambda line: line + b"\nsurprise\n")
        assert await link.exchange(b"a\n", read_line(), timeout=1) == b"a"
        assert link.is_dirty
        assert await link.exchange(b"b\n", read_line(), timeout=1) == b"b"
        tg.cancel_scope.cancel()


async def test_requests_are_served_in_fifo_order(
    peer_pair: tuple[MemoryStream, MemoryStream],
) -> None:
    host, board = peer_pair
    link = SerialLink(host)
    replies: dict[int, bytes] = {}
    async with anyio.create_task_group() as tg:
        peer = await start_peer(tg, board, upper, delay=lambda: 0.001)

        async def ask(n: int) -> None:
            replies[n] = await link.exchange(b"r%d\n" % n, read_line(), timeout=1)

        async with anyio.create_task_group() as askers:
            for n in range(20):
                askers.start_soon(ask, n)
        assert peer.lines == [b"r%d" % n for n in range(20)]
        assert replies == {n: b"R%d" % n for n in range(20)}
        tg.cancel_scope.cancel()


# -- validation and closing ----------------------------------------------------------------


def test_link_validates_its_settings() -> None:
    host, _ = memory_stream_pair()
    for bad in ({"default_timeout": 0}, {"quiet_time": -1}, {"drain_limit": float("nan")}):
        with pytest.raises(ValueError, match="positive"):
            SerialLink(host, **bad)
    with pytest.raises(ValueError, match="chunk_size"):
        SerialLink(host, chunk_size=0)


async def test_calls_validate_their_timeouts() -> None:
    host, _ = memory_stream_pair()
    link = SerialLink(host)
    with pytest.raises(ValueError, match="timeout"):
        await link.exchange(b"x", read_line(), timeout=0)
    with pytest.raises(ValueError, match="quiet_time"):
        await link.drain(0)
    with pytest.raises(ValueError, match="limit"):
        await link.drain(limit=-1)


async def test_a_closed_link_refuses_every_call() -> None:
    host, _ = memory_stream_pair()
    async with SerialLink(host) as link:
        pass
    assert link.is_closed and host.is_closed
    assert repr(link) == "<SerialLink 'memory-a' closed>"
    with pytest.raises(BoardDisconnectionError, match="link is closed"):
        await link.exchange(b"x\n", read_line(), timeout=1)
    with pytest.raises(BoardDisconnectionError, match="link is closed"):
        await link.send(b"x")
    with pytest.raises(BoardDisconnectionError, match="link is closed"):
        await link.command(b"x\n", read_line(), timeout=1)
    with acknowledge_later(), pytest.raises(BoardDisconnectionError, match="link is closed"):
        await link.command(b"x\n", read_line(), timeout=1)
    with pytest.raises(BoardDisconnectionError, match="link is closed"):
        await link.read_line(timeout=1)
    with pytest.raises(BoardDisconnectionError, match="link is closed"):
        await link.drain()
    link.close_now()  # idempotent


async def test_close_now_ends_a_waiting_exchange() -> None:
    host, _ = memory_stream_pair()
    link = SerialLink(host)
    with anyio.fail_after(1):
        async with anyio.create_task_group() as tg:

            async def close_soon() -> None:
                await anyio.sleep(0.01)
                link.close_now()

            tg.start_soon(close_soon)
            with pytest.raises(BoardDisconnectionError):
                await link.exchange(b"x\n", read_line(), timeout=5)
    assert link.is_dirty


# -- timeouts and the dirty drain ----------------------------------------------------------


async def test_timeout_names_the_port_and_the_request_and_marks_dirty(
    peer_pair: tuple[MemoryStream, MemoryStream],
) -> None:
    host, _ = peer_pair
    link = SerialLink(host, name="/dev/ttyACM0")
    with pytest.raises(CommunicationTimeoutError) as caught:
        await link.exchange(b"*IDN?\n", read_line(), timeout=0.02)
    message = str(caught.value)
    assert "/dev/ttyACM0" in message and "*IDN?" in message and "0.02 s" in message
    assert isinstance(caught.value, CommunicationError)
    assert link.is_dirty
    assert "dirty" in repr(link)


async def test_a_late_reply_is_drained_before_the_next_exchange(
    peer_pair: tuple[MemoryStream, MemoryStream],
) -> None:
    host, board = peer_pair
    link = SerialLink(host, quiet_time=0.05)
    delays = iter([0.03, 0.0])
    async with anyio.create_task_group() as tg:
        await start_peer(tg, board, upper, delay=lambda: next(delays))
        with pytest.raises(CommunicationTimeoutError):
            await link.exchange(b"slow\n", read_line(), timeout=0.02)
        # The reply to "slow" arrives about 10 ms late, during the next exchange's drain.
        assert await link.exchange(b"fast\n", read_line(), timeout=1) == b"FAST"
        assert not link.is_dirty
        tg.cancel_scope.cancel()


async def test_drain_discards_and_counts() -> None:
    host, board = memory_stream_pair()
    link = SerialLink(host)
    await board.send(b"old noise")
    link.mark_dirty()
    assert await link.drain(0.01) == 9
    assert not link.is_dirty
    assert await link.drain(0.01) == 0


async def test_a_line_that_never_goes_quiet_fails_the_drain() -> None:
    host, board = memory_stream_pair()
    link = SerialLink(host, quiet_time=0.25, drain_limit=0.4)
    link.mark_dirty()

    async def chatter() -> None:
        while True:
            await board.send(b"spam")
            await anyio.sleep(0.002)

    async with anyio.create_task_group() as tg:
        tg.start_soon(chatter)
        with pytest.raises(CommunicationError, match="kept sending"):
            await link.exchange(b"x\n", read_line(), timeout=1)
        assert link.is_dirty
        tg.cancel_scope.cancel()


async def test_a_send_that_cannot_complete_in_time_times_out() -> None:
    class StuckStream(MemoryStream):
        async def send(self, data: bytes) -> None:
            await anyio.sleep_forever()

    link = SerialLink(StuckStream("stuck"))
    with pytest.raises(CommunicationTimeoutError, match="could not send"):
        await link.send(b"\x02\x02", timeout=0.02)
    assert link.is_dirty


# -- failures of the stream ----------------------------------------------------------------


async def test_the_port_disappearing_mid_exchange_raises_board_disconnection() -> None:
    host, board = memory_stream_pair()
    link = SerialLink(host)
    async with anyio.create_task_group() as tg:

        async def unplug() -> None:
            await board.receive()
            board.close_now()

        tg.start_soon(unplug)
        with pytest.raises(BoardDisconnectionError, match="gone away"):
            await link.exchange(b"x\n", read_line(), timeout=1)
    with pytest.raises(BoardDisconnectionError):
        await link.exchange(b"y\n", read_line(), timeout=1)


class BrokenStream(MemoryStream):
    """A stream that fails with foreign exceptions."""

    def __init__(self, error: BaseException, *, on_send: bool) -> None:
        super().__init__("broken")
        self.error = error
        self.on_send = on_send

    async def send(self, data: bytes) -> None:
        if self.on_send:
            raise self.error

    async def receive(self, max_bytes: int = 4096) -> bytes:
        raise self.error


class BrokenNowaitStream(BrokenStream):
    """As :class:`BrokenStream`, failing on the paths that write at once and read by a deadline."""

    def send_nowait(self, data: bytes) -> bool:
        if self.on_send:
            raise self.error
        return True

    async def receive_by(self, deadline: float, max_bytes: int = 4096) -> bytes | None:
        raise self.error


BROKEN_STREAMS = [BrokenStream, BrokenNowaitStream]


@pytest.mark.parametrize("broken", BROKEN_STREAMS)
@pytest.mark.parametrize("on_send", [True, False])
async def test_os_errors_from_a_stream_become_communication_errors(
    on_send: bool, broken: type[BrokenStream]
) -> None:
    link = SerialLink(broken(OSError(5, "Input/output error"), on_send=on_send))
    with pytest.raises(CommunicationError, match="Input/output error") as caught:
        await link.exchange(b"x\n", read_line(), timeout=1)
    assert not isinstance(caught.value, BoardDisconnectionError)
    assert isinstance(caught.value.__cause__, OSError)


@pytest.mark.parametrize("broken", BROKEN_STREAMS)
@pytest.mark.parametrize("on_send", [True, False])
@pytest.mark.parametrize(
    "error", [anyio.EndOfStream(), anyio.BrokenResourceError(), anyio.ClosedResourceError()]
)
async def test_anyio_stream_errors_become_board_disconnection(
    error: Exception, on_send: bool, broken: type[BrokenStream]
) -> None:
    link = SerialLink(broken(error, on_send=on_send))
    with pytest.raises(BoardDisconnectionError, match="has gone"):
        await link.exchange(b"x\n", read_line(), timeout=1)
    assert link.is_dirty


@pytest.mark.parametrize(
    ("error", "raised"),
    [
        (OSError(5, "Input/output error"), CommunicationError),
        (CommunicationTimeoutError("the stream's own"), CommunicationTimeoutError),
        (AssertionError("script broken"), AssertionError),
    ],
)
async def test_an_exchange_whose_bytes_fail_at_once_is_logged_and_mapped(
    error: BaseException, raised: type[BaseException], caplog: pytest.LogCaptureFixture
) -> None:
    link = SerialLink(BrokenNowaitStream(error, on_send=True), name="/dev/ttyACM7")
    caplog.set_level(TRACE, logger="j5aio.wire")
    with pytest.raises(raised) as caught:
        await link.exchange(b"x\n", read_line(), timeout=1)
    assert type(caught.value) is raised
    assert link.is_dirty
    records = [r for r in caplog.records if r.name == "j5aio.wire./dev/ttyACM7"]
    assert [r.getMessage() for r in records] == ["-> b'x\\n'"]


async def test_a_send_whose_bytes_fail_at_once_is_logged_and_leaves_the_link_dirty(
    caplog: pytest.LogCaptureFixture,
) -> None:
    link = SerialLink(BrokenNowaitStream(OSError(5, "Input/output error"), on_send=True), name="s")
    caplog.set_level(TRACE, logger="j5aio.wire")
    ran: list[bool] = []
    with pytest.raises(CommunicationError, match="Input/output error"):
        await link.send(b"x\n", timeout=1, then=lambda: ran.append(True))
    assert link.is_dirty
    assert not ran  # nothing went: what a backend remembers is not updated
    assert [r.getMessage() for r in caplog.records if r.name == "j5aio.wire.s"] == ["-> b'x\\n'"]


async def _write_by(link: SerialLink, how: str) -> None:
    """Write ``x`` through one of the paths that write without reading a reply."""
    if how == "send":
        await link.send(b"x\n", timeout=1)
    else:  # a command whose acknowledgement is read later
        with acknowledge_later():
            await link.command(b"x\n", read_line(), timeout=1)


@pytest.mark.parametrize("how", ["send", "command later"])
@pytest.mark.parametrize(
    ("error", "raised"),
    [
        (OSError(5, "Input/output error"), CommunicationError),
        (anyio.BrokenResourceError(), BoardDisconnectionError),
        (CommunicationTimeoutError("the stream's own"), CommunicationTimeoutError),
        (AssertionError("script broken"), AssertionError),
    ],
)
@pytest.mark.parametrize("broken", BROKEN_STREAMS)
async def test_a_write_that_fails_raises_the_same_on_every_path(
    how: str, error: BaseException, raised: type[BaseException], broken: type[BrokenStream]
) -> None:
    link = SerialLink(broken(error, on_send=True))
    with pytest.raises(raised) as caught:
        await _write_by(link, how)
    assert type(caught.value) is raised
    if raised is CommunicationError:
        assert "sending b'x\\n' failed: [Errno 5] Input/output error" in str(caught.value)
        assert caught.value.__cause__ is error
    assert link.acknowledgement_owed is None  # nothing was written, so nothing is owed


@pytest.mark.parametrize("how", ["send", "command later"])
async def test_every_write_path_logs_the_bytes_at_trace(
    how: str, caplog: pytest.LogCaptureFixture
) -> None:
    host, board = memory_stream_pair()
    link = SerialLink(host, name="/dev/ttyACM8")
    caplog.set_level(TRACE, logger="j5aio.wire")
    await _write_by(link, how)
    assert await board.receive() == b"x\n"
    records = [r for r in caplog.records if r.name == "j5aio.wire./dev/ttyACM8"]
    assert [r.getMessage() for r in records] == ["-> b'x\\n'"]


async def test_each_request_reads_the_acknowledgement_owed_first() -> None:
    host, board = memory_stream_pair()
    link = SerialLink(host)
    async with anyio.create_task_group() as tg:
        peer = await start_peer(tg, board, lambda line: b"ACK\n" if line != b"q" else b"42\n")
        with acknowledge_later():
            await link.command(b"a\n", read_line(), timeout=1)
            assert link.acknowledgement_owed == b"a\n"
            assert await link.exchange(b"q\n", read_line(), timeout=1) == b"42"
            await link.command(b"b\n", read_line(), timeout=1)
            await link.command(b"c\n", read_line(), timeout=1)  # reads b's ACK first
            assert link.acknowledgement_owed == b"c\n"
            await link.send(b"d\n", timeout=1)  # reads c's ACK first
            assert link.acknowledgement_owed is None
        await link.exchange(b"q\n", read_line(), timeout=1)
        await anyio.wait_all_tasks_blocked()  # the peer reads in a task of its own
        assert peer.lines == [b"a", b"q", b"b", b"c", b"d", b"q"]
        tg.cancel_scope.cancel()


async def test_a_resynchronisation_probe_is_logged_and_its_failed_write_wrapped(
    caplog: pytest.LogCaptureFixture,
) -> None:
    link = SerialLink(BrokenStream(OSError(5, "Input/output error"), on_send=True), name="p")
    link.set_resync(b"?", b"!")
    link.mark_dirty()
    caplog.set_level(TRACE, logger="j5aio.wire")
    with pytest.raises(CommunicationError, match=r"sending b'\?' failed") as caught:
        await link.exchange(b"x\n", read_line(), timeout=1)
    assert not isinstance(caught.value, BoardDisconnectionError)
    assert [r.getMessage() for r in caplog.records if r.name == "j5aio.wire.p"] == ["-> b'?'"]


async def test_other_exceptions_from_a_stream_are_not_hidden() -> None:
    link = SerialLink(BrokenStream(AssertionError("script broken"), on_send=True))
    with pytest.raises(AssertionError, match="script broken"):
        await link.exchange(b"x\n", read_line(), timeout=1)


async def test_a_corrupted_reply_is_returned_as_it_came() -> None:
    host, board = memory_stream_pair()
    faulty = FaultyStream(host)
    link = SerialLink(faulty)
    async with anyio.create_task_group() as tg:
        await start_peer(tg, board, lambda line: b"+ OK\n")
        faulty.corrupt_next_reply()
        assert await link.exchange(b"x\n", read_line(), timeout=1) == b"\xd4 OK"
        assert await link.exchange(b"y\n", read_line(), timeout=1) == b"+ OK"
        tg.cancel_scope.cancel()


async def test_a_reply_with_a_corrupted_terminator_times_out_then_recovers() -> None:
    host, board = memory_stream_pair()
    faulty = FaultyStream(host)
    link = SerialLink(faulty, quiet_time=0.01)
    async with anyio.create_task_group() as tg:
        await start_peer(tg, board, lambda line: line + b"\n")
        faulty.corrupt_next_reply(lambda reply: reply.replace(b"\n", b"?"))
        with pytest.raises(CommunicationTimeoutError, match=r"received so far: b'first\?'"):
            await link.exchange(b"first\n", read_line(), timeout=0.3)
        assert await link.exchange(b"second\n", read_line(), timeout=1) == b"second"
        tg.cancel_scope.cancel()


async def test_a_garbage_reply_raises_unexpected_reply_and_marks_dirty() -> None:
    host, board = memory_stream_pair()
    link = SerialLink(host, quiet_time=0.01)
    async with anyio.create_task_group() as tg:
        await start_peer(tg, board, lambda line: b"\xff" * 64 + b"\n")
        with pytest.raises(UnexpectedReplyError, match=r"bad reply to b'x\\n'"):
            await link.exchange(b"x\n", read_line(max_length=16), timeout=1)
        assert link.is_dirty
        tg.cancel_scope.cancel()


# -- the wire log --------------------------------------------------------------------------


async def test_wire_bytes_are_logged_at_trace(caplog: pytest.LogCaptureFixture) -> None:
    host, board = memory_stream_pair()
    link = SerialLink(host, name="/dev/ttyACM9")
    caplog.set_level(TRACE, logger="j5aio.wire")
    await board.send(b"hi\n")
    await link.exchange(b"ping\n", read_line(), timeout=1)
    records = [r for r in caplog.records if r.name == "j5aio.wire./dev/ttyACM9"]
    assert [r.levelname for r in records] == ["TRACE", "TRACE"]
    assert [r.getMessage() for r in records] == ["-> b'ping\\n'", "<- b'hi\\n'"]


async def test_draining_and_discarding_are_logged_at_debug(
    caplog: pytest.LogCaptureFixture,
) -> None:
    host, board = memory_stream_pair()
    link = SerialLink(host, quiet_time=0.01)
    caplog.set_level(logging.DEBUG, logger="j5aio.backends.hardware.transports.serial_link")
    await board.send(b"one\ntwo\n")
    await link.read_line(timeout=1)
    with pytest.raises(CommunicationTimeoutError):
        await link.exchange(b"x\n", read_line(), timeout=0.01)
    await board.send(b"late\n")
    with pytest.raises(CommunicationTimeoutError):
        await link.exchange(b"y\n", read_line(), timeout=0.01)
    text = caplog.text
    assert "discarding stale input b'two\\n'" in text
    assert "drained 5 bytes" in text


# -- cancellation ----------------------------------------------------------------------------


async def test_a_caller_cancelled_mid_exchange_still_consumes_its_reply(
    peer_pair: tuple[MemoryStream, MemoryStream],
) -> None:
    host, board = peer_pair
    link = SerialLink(host)
    async with anyio.create_task_group() as tg:
        peer = await start_peer(tg, board, upper, delay=lambda: 0.03)
        with anyio.move_on_after(0.01) as scope:
            await link.exchange(b"first\n", read_line(), timeout=1)
            await anyio.lowlevel.checkpoint()
        assert scope.cancelled_caught
        assert peer.lines == [b"first"]
        assert not link.is_dirty and link.buffered == b""
        assert await link.exchange(b"second\n", read_line(), timeout=1) == b"SECOND"
        tg.cancel_scope.cancel()


async def test_a_caller_cancelled_while_waiting_for_the_lock_sends_nothing(
    peer_pair: tuple[MemoryStream, MemoryStream],
) -> None:
    host, board = peer_pair
    link = SerialLink(host)
    async with anyio.create_task_group() as tg:
        peer = await start_peer(tg, board, upper, delay=lambda: 0.03)
        tg.start_soon(link.exchange, b"first\n", read_line())
        await anyio.sleep(0.005)
        with anyio.move_on_after(0.005) as scope:
            await link.exchange(b"never\n", read_line(), timeout=1)
        assert scope.cancelled_caught
        assert await link.exchange(b"third\n", read_line(), timeout=1) == b"THIRD"
        assert peer.lines == [b"first", b"third"]
        tg.cancel_scope.cancel()


async def test_native_task_cancel_does_not_tear_an_exchange(
    peer_pair: tuple[MemoryStream, MemoryStream],
) -> None:
    host, board = peer_pair
    link = SerialLink(host, quiet_time=0.02)
    seen: list[bytes] = []
    async with anyio.create_task_group() as tg:
        await start_peer(tg, board, upper, delay=lambda: 0.01)
        task = asyncio.ensure_future(
            link.exchange(b"torn\n", read_line(), timeout=1, then=seen.append)
        )
        await anyio.sleep(0.002)
        task.cancel()  # asyncio-native: breaks through anyio shields, not through this
        with pytest.raises(asyncio.CancelledError):
            await task
        # The exchange ran to its end: its reply was consumed and its callback ran.
        assert seen == [b"TORN"]
        assert not link.is_dirty and link.buffered == b""
        assert await link.exchange(b"next\n", read_line(), timeout=1) == b"NEXT"
        tg.cancel_scope.cancel()


async def test_asyncio_timeout_around_an_exchange_becomes_timeout_error(
    peer_pair: tuple[MemoryStream, MemoryStream],
) -> None:
    host, board = peer_pair
    link = SerialLink(host)
    seen: list[bytes] = []
    async with anyio.create_task_group() as tg:
        await start_peer(tg, board, upper, delay=lambda: 0.02)
        with pytest.raises(TimeoutError):
            async with asyncio.timeout(0.005):
                await link.exchange(b"slow\n", read_line(), timeout=1, then=seen.append)
        assert seen == [b"SLOW"]
        assert await asyncio.wait_for(link.exchange(b"x\n", read_line(), timeout=1), 1) == b"X"
        tg.cancel_scope.cancel()


async def test_then_runs_after_a_send_and_its_errors_reach_the_caller(
    peer_pair: tuple[MemoryStream, MemoryStream],
) -> None:
    host, board = peer_pair
    link = SerialLink(host)
    sent: list[str] = []
    await link.send(b"\x02\x80", then=lambda: sent.append("done"))
    assert sent == ["done"]
    await board.send(b"reply\n")

    def refuse(reply: bytes) -> None:
        raise ValueError(f"refused {reply!r}")

    with pytest.raises(ValueError, match="refused b'reply'"):
        await link.exchange(b"", read_line(), timeout=1, then=refuse)


async def test_a_send_cancelled_by_anyio_part_way_still_goes_and_runs_then(
    peer_pair: tuple[MemoryStream, MemoryStream],
) -> None:
    # The caller is cancelled while its send waits for a dirty link's probe answer: the
    # send goes on to the end, and the cancellation takes effect afterwards.
    host, board = peer_pair
    link = SerialLink(host, drain_limit=5)
    link.set_resync(b"?", b"!")
    link.mark_dirty()
    sent: list[str] = []

    async def answer_then_cancel(scope: anyio.CancelScope) -> None:
        assert await board.receive() == b"?"
        scope.cancel()
        await anyio.sleep(0.01)
        await board.send(b"!")

    async with anyio.create_task_group() as tg:
        with anyio.CancelScope() as scope:
            tg.start_soon(answer_then_cancel, scope)
            await link.send(b"go\n", then=lambda: sent.append("done"))
            assert sent == ["done"]
            await anyio.lowlevel.checkpoint()  # the cancellation, held back, lands here
    assert scope.cancelled_caught
    assert sent == ["done"]
    assert await board.receive() == b"go\n"


async def test_a_send_yields_to_the_event_loop(
    peer_pair: tuple[MemoryStream, MemoryStream],
) -> None:
    # A loop of sends (no replies to wait for) must leave other tasks and signal
    # handlers room to run.
    host, _board = peer_pair
    link = SerialLink(host)
    ran: list[str] = []

    async def other_task() -> None:
        ran.append("other task")

    async with anyio.create_task_group() as tg:
        tg.start_soon(other_task)
        await link.send(b"go\n")
        assert ran == ["other task"]


async def test_a_send_torn_by_task_cancel_before_its_bytes_went_sends_nothing(
    peer_pair: tuple[MemoryStream, MemoryStream],
) -> None:
    # The probe of a dirty link is never answered: Task.cancel tears the send while it
    # waits, before the command went. Nothing of it is sent, ``then`` does not run, and
    # the link stays dirty for the next caller.
    host, board = peer_pair
    link = SerialLink(host, drain_limit=5)
    link.set_resync(b"?", b"!")
    link.mark_dirty()
    sent: list[str] = []
    with pytest.raises(TimeoutError):
        async with asyncio.timeout(0.01):
            await link.send(b"go\n", then=lambda: sent.append("done"))
    assert sent == []
    assert link.is_dirty
    assert await board.receive() == b"?"

    async def answer_the_probe() -> None:
        assert await board.receive() == b"?"
        await board.send(b"!")

    async with anyio.create_task_group() as tg:
        tg.start_soon(answer_the_probe)
        await link.send(b"go\n", then=lambda: sent.append("done"))
    assert sent == ["done"]
    assert await board.receive() == b"go\n"


@dataclass
class StressResult:
    """What a cancellation stress run observed."""

    attempts: int = 0
    cancelled_waiting: int = 0  # cancelled before its exchange began: nothing was sent
    cancelled_mid_exchange: int = 0  # cancelled after its exchange began (shield held)
    timeouts: int = 0
    replies: int = 0
    strays: int = 0  # replies that answered another request

    @property
    def cancellations(self) -> int:
        return self.cancelled_waiting + self.cancelled_mid_exchange


def sequence_peer(rng: random.Random, max_delay: float) -> tuple[Responder, Callable[[], float]]:
    def respond(line: bytes) -> bytes:
        assert line.startswith(b"REQ ")
        return b"REP " + line[4:] + b"\n"

    return respond, lambda: rng.uniform(0, max_delay)


async def stress_until(
    link: SerialLink,
    rng: random.Random,
    enough: Callable[[StressResult], bool],
    *,
    rounds: int = 20,
    **workload: Any,
) -> StressResult:
    """Run :func:`stress` rounds on ``link`` until ``enough`` of each outcome has happened.

    How many exchanges time out, are answered or are cancelled depends on the machine's
    timing (a loaded machine answers later); the checks that matter (no stray reply) hold
    in every round, so rounds are added until the workload has exercised each outcome.
    """
    total = StressResult()
    for _ in range(rounds):
        result = await stress(link, rng, **workload)
        for name in (
            "attempts",
            "cancelled_waiting",
            "cancelled_mid_exchange",
            "timeouts",
            "replies",
            "strays",
        ):
            setattr(total, name, getattr(total, name) + getattr(result, name))
        if enough(total):
            break
    return total


async def stress(
    link: SerialLink,
    rng: random.Random,
    *,
    workers: int,
    per_worker: int,
    max_deadline: float,
    timeout: float,
) -> StressResult:
    result = StressResult()

    async def worker(worker_id: int) -> None:
        for n in range(per_worker):
            tag = b"%d.%d" % (worker_id, n)
            result.attempts += 1
            got_reply = False
            with anyio.move_on_after(rng.uniform(0, max_deadline)) as scope:
                try:
                    reply = await link.exchange(b"REQ " + tag + b"\n", read_line(), timeout=timeout)
                except CommunicationTimeoutError:
                    result.timeouts += 1
                    result.cancelled_mid_exchange += scope.cancel_called
                    continue
                got_reply = True
                result.replies += 1
                result.strays += reply != b"REP " + tag
                # The deadline passed while the (shielded) exchange ran: its caller was
                # cancelled mid-exchange, and the exchange still consumed its own reply.
                result.cancelled_mid_exchange += scope.cancel_called
                await anyio.lowlevel.checkpoint()  # the caller moves on to other work
            if scope.cancelled_caught and not got_reply:
                result.cancelled_waiting += 1

    async with anyio.create_task_group() as tg:
        for worker_id in range(workers):
            tg.start_soon(worker, worker_id)
    return result


async def test_thousands_of_random_cancellations_leave_no_stray_reply() -> None:
    rng = random.Random(20240611)
    host, board = memory_stream_pair()
    recording = RecordingStream(host)
    link = SerialLink(recording)
    respond, delay = sequence_peer(rng, max_delay=0.002)
    async with anyio.create_task_group() as tg:
        peer = await start_peer(tg, board, respond, delay=delay)
        result = await stress_until(
            link,
            rng,
            lambda r: r.cancellations >= 2000 and r.cancelled_mid_exchange >= 500,
            workers=4,
            per_worker=1000,
            max_deadline=0.004,
            timeout=1.0,
        )
        # One last uncancelled exchange proves the line is clean.
        assert await link.exchange(b"REQ final\n", read_line(), timeout=1) == b"REP final"
        tg.cancel_scope.cancel()
    print(
        f"\nstress: {result.attempts} exchanges, {result.cancellations} cancelled "
        f"({result.cancelled_mid_exchange} mid-exchange, {result.cancelled_waiting} while "
        f"queued), {result.replies} replies, {result.strays} strays"
    )
    assert result.strays == 0
    assert result.timeouts == 0
    assert result.cancellations >= 2000
    assert result.cancelled_mid_exchange >= 500
    # Every request on the wire got exactly its own reply, and all were consumed.
    assert len(peer.lines) == result.replies + 1
    assert recording.received.count(b"REP ") == len(peer.lines)
    assert link.buffered == b"" and not link.is_dirty


async def test_random_cancellations_and_timeouts_leave_no_stray_reply() -> None:
    rng = random.Random(7)
    host, board = memory_stream_pair()
    link = SerialLink(host, quiet_time=0.03)
    # Replies take up to 4 ms; exchanges time out after 2 ms: many replies come late,
    # and the dirty drain must swallow every one of them.
    respond, delay = sequence_peer(rng, max_delay=0.004)
    async with anyio.create_task_group() as tg:
        await start_peer(tg, board, respond, delay=delay)
        result = await stress_until(
            link,
            rng,
            lambda r: r.timeouts >= 10 and r.replies >= 10 and r.cancellations >= 100,
            workers=3,
            per_worker=200,
            max_deadline=0.02,
            timeout=0.002,
        )
        tg.cancel_scope.cancel()
    print(f"\nstress with timeouts: {result}")
    assert result.strays == 0
    # How many of each happen depends on timing; enough of each must happen.
    assert result.timeouts >= 10
    assert result.replies >= 10
    assert result.cancellations >= 100


async def test_the_stress_detects_strays_when_the_exchange_is_not_shielded() -> None:
    """Control experiment: the same workload through a naive exchange does leave strays."""
    rng = random.Random(3)
    host, board = memory_stream_pair()
    respond, delay = sequence_peer(rng, max_delay=0.002)
    buffer = bytearray()
    lock = anyio.Lock()
    strays = 0

    async def naive_exchange(stream: ByteStream, request: bytes) -> bytes:
        async with lock:
            await stream.send(request)
            while b"\n" not in buffer:
                buffer.extend(await stream.receive())
            line, _, rest = bytes(buffer).partition(b"\n")
            buffer[:] = rest
            return line

    async with anyio.create_task_group() as tg:
        await start_peer(tg, board, respond, delay=delay)
        for n in range(300):
            with anyio.move_on_after(rng.uniform(0, 0.003)):
                reply = await naive_exchange(host, b"REQ %d\n" % n)
                strays += reply != b"REP %d" % n
        tg.cancel_scope.cancel()
    assert strays > 0


async def test_a_dirty_link_with_a_probe_resynchronises_before_its_next_exchange(
    peer_pair: tuple[MemoryStream, MemoryStream],
) -> None:
    host, board = peer_pair
    link = SerialLink(host)
    with pytest.raises(ValueError, match="must not be empty"):
        link.set_resync(b"", b"x")
    link.set_resync(b"v\n", b"V\r\n")
    assert link.resync_probe == (b"v\n", b"V\r\n")
    async with anyio.create_task_group() as tg:
        peer = await start_peer(tg, board, upper)
        await board.send(b"STALE\r\nOLD")  # late replies to requests that timed out
        link.mark_dirty()
        assert await link.exchange(b"next\n", read_line(), timeout=1) == b"NEXT"
        assert not link.is_dirty
        assert peer.lines == [b"v", b"next"]
        tg.cancel_scope.cancel()


async def test_a_line_probe_discards_whole_lines_up_to_its_fresh_answer(
    peer_pair: tuple[MemoryStream, MemoryStream],
) -> None:
    host, board = peer_pair
    link = SerialLink(host)
    nonces = iter([b"n1", b"n2"])

    def probe() -> tuple[bytes, bytes]:
        nonce = next(nonces)
        return b"echo " + nonce + b"\n", b"ECHO " + nonce.upper()

    link.set_resync_line(probe)
    assert link.resync_probe is None  # a fresh probe each time: no fixed pair
    async with anyio.create_task_group() as tg:
        peer = await start_peer(tg, board, upper)
        # Late replies: one that contains the answer but is not it, and an old answer.
        await board.send(b"XECHO N1\r\nECHO N0\r\n")
        link.mark_dirty()
        assert await link.exchange(b"next\n", read_line(), timeout=1) == b"NEXT"
        assert peer.lines == [b"echo n1", b"next"]
        await board.send(b"LATE\n")
        link.mark_dirty()
        await link.send(b"x\n")
        assert not link.is_dirty
        with anyio.fail_after(5):  # send returns once the bytes have gone; the peer reads later
            while peer.lines[-1:] != [b"x"]:
                await anyio.lowlevel.checkpoint()
        assert peer.lines[-2:] == [b"echo n2", b"x"]
        tg.cancel_scope.cancel()


async def test_after_a_probe_went_unanswered_the_next_waits_for_a_quiet_line_first(
    peer_pair: tuple[MemoryStream, MemoryStream],
) -> None:
    host, board = peer_pair
    link = SerialLink(host, drain_limit=0.05)
    link.set_resync_line(lambda: (b"v\n", b"V"))
    link.mark_dirty()
    with pytest.raises(CommunicationError, match="could not resynchronise"):
        await link.send(b"x\n")
    assert link.is_dirty
    async with anyio.create_task_group() as tg:
        peer = await start_peer(tg, board, upper)
        # The first probe's answer comes late: it is drained, not taken for the second's.
        await board.send(b"V\r\n")
        assert await link.exchange(b"next\n", read_line(), timeout=1) == b"NEXT"
        assert peer.lines[-2:] == [b"v", b"next"]
        tg.cancel_scope.cancel()


async def test_a_probe_that_is_never_answered_leaves_the_link_dirty(
    peer_pair: tuple[MemoryStream, MemoryStream],
) -> None:
    host, _ = peer_pair
    link = SerialLink(host, drain_limit=0.05)
    link.set_resync(b"v", b"SRduino:1\n")
    link.mark_dirty()
    with pytest.raises(CommunicationError, match="could not resynchronise"):
        await link.send(b"x")
    assert link.is_dirty


async def test_run_to_completion_logs_the_error_of_a_cancelled_callers_work(
    caplog: pytest.LogCaptureFixture,
) -> None:
    from j5aio.backends.hardware.transports.completion import run_to_completion

    async def failing() -> None:
        await anyio.sleep(0.02)
        raise CommunicationError("the board said no")

    task = asyncio.ensure_future(run_to_completion(failing))
    await anyio.sleep(0.005)
    task.cancel()
    with (
        caplog.at_level(logging.DEBUG, logger="j5aio.backends.hardware.transports"),
        pytest.raises(asyncio.CancelledError),
    ):
        await task
    assert "the board said no" in caplog.text


# -- sending synchronously (the safety net) ------------------------------------------------


async def test_send_now_reaches_the_board_without_awaiting() -> None:
    host, board = memory_stream_pair("host", "board")
    recorder = RecordingStream(FaultyStream(host))
    link = SerialLink(recorder, name="memory")
    link.send_now(b"brake\n")
    assert await board.receive() == b"brake\n"
    assert recorder.sent == b"brake\n"
    assert link.is_dirty
    board.close_now()
    with pytest.raises(BoardDisconnectionError, match="other end has gone"):
        link.send_now(b"x")
    link.close_now()
    with pytest.raises(BoardDisconnectionError, match="link is closed"):
        link.send_now(b"x")
    with pytest.raises(BoardDisconnectionError, match="stream is closed"):
        host.send_now(b"x", 0.1)


class NoSyncStream(ByteStream):
    """A stream that keeps the default: it cannot send synchronously."""

    name = "no-sync"
    is_closed = False

    async def send(self, data: bytes) -> None:
        raise OSError("not used")

    async def receive(self, max_bytes: int = 4096) -> bytes:
        raise OSError("not used")

    def close_now(self) -> None:
        pass


class OSErrorStream(NoSyncStream):
    def send_now(self, data: bytes, timeout: float) -> None:
        raise OSError("the device is gone")


def test_send_now_failures_are_communication_errors() -> None:
    with pytest.raises(CommunicationError, match="cannot send synchronously"):
        SerialLink(NoSyncStream()).send_now(b"x")
    with pytest.raises(CommunicationError, match="sending b'x' failed: the device is gone"):
        SerialLink(OSErrorStream()).send_now(b"x")


# -- tagging only while a reply may be outstanding ------------------------------------------


async def test_a_request_is_tagged_only_while_a_late_reply_may_come(
    peer_pair: tuple[MemoryStream, MemoryStream],
) -> None:
    host, board = peer_pair
    link = SerialLink(host)
    tagged: list[bytes] = []

    def tag(request: bytes) -> Callable[[], tuple[bytes, ReplyReader[bytes]]]:
        def make() -> tuple[bytes, ReplyReader[bytes]]:
            tagged.append(request)
            return b"#7 " + request, matching(read_line(), lambda line: line.startswith(b"#7 "))

        return make

    async def answer(expected: bytes, reply: bytes) -> None:
        assert await board.receive() == expected
        await board.send(reply)

    async with anyio.create_task_group() as tg:
        # A clean link: the plain request goes, and the tagged one is never made.
        tg.start_soon(answer, b"a\n", b"A\n")
        assert await link.exchange(b"a\n", read_line(), timeout=1, when_dirty=tag(b"a\n")) == b"A"
        assert tagged == []
        # The board does not answer in time: the link is dirty...
        with pytest.raises(CommunicationTimeoutError):
            await link.exchange(b"b\n", read_line(), timeout=0.01, when_dirty=tag(b"b\n"))
        assert await board.receive() == b"b\n"
        assert link.is_dirty
        # ...so the next request is tagged, and the late reply to "b" is skipped.
        await board.send(b"B\n")
        tg.start_soon(answer, b"#7 c\n", b"#7 C\n")
        reply = await link.exchange(b"c\n", read_line(), timeout=1, when_dirty=tag(b"c\n"))
        assert reply == b"#7 C"
        assert tagged == [b"c\n"]
        assert not link.is_dirty and link.buffered == b""
        # Its reply came after everything owed: plain requests again.
        tg.start_soon(answer, b"d\n", b"D\n")
        assert await link.exchange(b"d\n", read_line(), timeout=1, when_dirty=tag(b"d\n")) == b"D"
        assert tagged == [b"c\n"]


async def test_a_correlating_reader_skips_a_foreign_reply_on_a_clean_link(
    peer_pair: tuple[MemoryStream, MemoryStream], caplog: pytest.LogCaptureFixture
) -> None:
    host, board = peer_pair
    link = SerialLink(host)
    ours = matching(read_line(), lambda line: line.startswith(b"#3 "))

    async def answer() -> None:
        assert await board.receive() == b"#3 v\n"
        await board.send(b"#2 late\n")  # a reply to some other request: not this one's
        await anyio.sleep(0.01)
        await board.send(b"#3 V\n")

    caplog.set_level(TRACE, logger="j5aio.wire")
    async with anyio.create_task_group() as tg:
        tg.start_soon(answer)
        assert await link.exchange(b"#3 v\n", ours, timeout=1) == b"#3 V"
    assert not link.is_dirty and link.buffered == b""
    assert "<-" in caplog.text  # each chunk received is on the wire trace


# -- late replies that overtake (line protocols) ---------------------------------------------


def _echo_probes() -> Callable[[], tuple[bytes, bytes]]:
    count = iter(range(1, 1000))

    def probe() -> tuple[bytes, bytes]:
        nonce = b"n%d" % next(count)
        return b"echo " + nonce + b"\n", b"ECHO " + nonce.upper()

    return probe


async def test_while_a_late_line_is_owed_requests_go_between_two_probes(
    peer_pair: tuple[MemoryStream, MemoryStream],
) -> None:
    host, board = peer_pair
    link = SerialLink(host, drain_limit=0.2)
    link.set_resync_line(_echo_probes())
    held: list[bytes] = []

    def answer(line: bytes) -> bytes:
        if line == b"first":
            held.append(b"FIRST\r\n")  # answered later, after later replies
            return b""
        return upper(line)

    async with anyio.create_task_group() as tg:
        peer = await start_peer(tg, board, answer)
        with pytest.raises(CommunicationTimeoutError):
            await link.exchange(b"first\n", read_line(), timeout=0.02)
        assert await link.exchange(b"second\n", read_line(), timeout=1) == b"SECOND"
        assert peer.lines[-3:] == [b"echo n1", b"second", b"echo n2"]
        # The late line lands amid the next reply: an error, not a wrong answer.
        peer.respond = lambda line: (
            (held.pop() if held and line == b"third" else b"") + (upper(line))
        )
        with pytest.raises(CommunicationError, match="cannot be told"):
            await link.exchange(b"third\n", read_line(), timeout=1)
        assert not link.is_dirty or not link.buffered
        # Every owed line has come: plain again.
        peer.respond = upper
        assert await link.exchange(b"fourth\n", read_line(), timeout=1) == b"FOURTH"
        assert peer.lines[-2:] == [b"echo n4", b"fourth"], peer.lines
        tg.cancel_scope.cancel()


async def test_a_bracketed_exchange_torn_by_task_cancel_still_reads_its_own_reply(
    peer_pair: tuple[MemoryStream, MemoryStream],
) -> None:
    host, board = peer_pair
    link = SerialLink(host, drain_limit=0.2)
    link.set_resync_line(_echo_probes())
    seen: list[bytes] = []
    async with anyio.create_task_group() as tg:
        peer = await start_peer(tg, board, lambda line: b"" if line == b"lost" else upper(line))
        with pytest.raises(CommunicationTimeoutError):
            await link.exchange(b"lost\n", read_line(), timeout=0.02)
        peer.delay = lambda: 0.01

        async def caller() -> None:
            await link.exchange(b"kept\n", read_line(), timeout=1, then=seen.append)

        task = asyncio.ensure_future(caller())
        await anyio.sleep(0.003)  # the bracket is on its way; no answer has come yet
        task.cancel()
        with pytest.raises(asyncio.CancelledError):
            await task
        assert seen == [b"KEPT"]  # the reply, not a probe's answer
        assert peer.lines[-3:] == [b"echo n1", b"kept", b"echo n2"]
        tg.cancel_scope.cancel()

"""Tests of serial streams: a real pseudo-terminal, pyserial URLs, and opening errors."""

from __future__ import annotations

import asyncio
import contextlib
import errno
import gc
import logging
import os
import select
import socket
import sys
import threading
import time
import tty
from collections.abc import AsyncIterator, Callable, Iterator
from typing import Any

import anyio
import pytest
import serial

from j5aio.backends.hardware.transports import (
    ByteStream,
    PortInfo,
    SerialLink,
    SerialStream,
    line_starts_with,
    open_serial_stream,
    read_line,
    read_lines_until,
)
from j5aio.backends.hardware.transports import serial_stream as serial_stream_module
from j5aio.errors import BoardDisconnectionError, CommunicationError

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="needs POSIX pseudo-terminals")


class PtyBoard:
    """A board on the master side of a pseudo-terminal, answering lines in the event loop."""

    def __init__(self) -> None:
        self.master, self.slave = os.openpty()
        tty.setraw(self.slave)
        os.set_blocking(self.master, False)
        self.path = os.ttyname(self.slave)
        self.received = bytearray()
        self.respond: Callable[[bytes], bytes] | None = None
        self._buffer = bytearray()
        self._loop: asyncio.AbstractEventLoop | None = None

    def answer_lines(self, respond: Callable[[bytes], bytes]) -> None:
        """Start answering each line written to the port with ``respond(line)``."""
        self.respond = respond
        self._loop = asyncio.get_running_loop()
        self._loop.add_reader(self.master, self._readable)

    def _readable(self) -> None:
        try:
            data = os.read(self.master, 4096)
        except OSError:
            return
        self.received += data
        self._buffer += data
        while self.respond is not None and b"\n" in self._buffer:
            line, _, rest = bytes(self._buffer).partition(b"\n")
            self._buffer = bytearray(rest)
            reply = self.respond(line)
            if reply:
                os.write(self.master, reply)

    def write(self, data: bytes) -> None:
        os.write(self.master, data)

    def unplug(self) -> None:
        """Close the master side: the port vanishes, as when a USB adapter is pulled."""
        if self._loop is not None:
            self._loop.remove_reader(self.master)
            self._loop = None
        if self.master >= 0:
            os.close(self.master)
            self.master = -1

    def close(self) -> None:
        self.unplug()
        os.close(self.slave)


@pytest.fixture
def board() -> Iterator[PtyBoard]:
    pty_board = PtyBoard()
    yield pty_board
    pty_board.close()


@pytest.fixture
async def stream(board: PtyBoard) -> AsyncIterator[SerialStream]:
    opened = await open_serial_stream(board.path, 115200)
    yield opened
    opened.close_now()


def sb_arduino(line: bytes) -> bytes:
    return b"# " + line + b"\r\n> H\r\n+ OK\r\n"


# -- a real pseudo-terminal ----------------------------------------------------------------


async def test_lines_are_exchanged_through_a_pty(board: PtyBoard, stream: SerialStream) -> None:
    assert isinstance(stream, ByteStream)
    assert stream.name == board.path
    assert stream.serial.is_open
    board.answer_lines(lambda line: line[::-1] + b"\n")
    link = SerialLink(stream)
    assert await link.exchange(b"hello\n", read_line(), timeout=1) == b"olleh"
    assert await link.exchange(b"abc\n", read_line(), timeout=1) == b"cba"
    assert board.received == b"hello\nabc\n"


async def test_banner_then_multi_line_replies_through_a_pty(board: PtyBoard) -> None:
    async with SerialLink(await open_serial_stream(board.path, 115200)) as link:
        # The board boots when the port opens (opening discards older input).
        board.write(b"# Booted\r\n# SBDuino GPIO v2019.8.0\r\n")
        assert await link.read_line(timeout=1) == b"# Booted"
        assert await link.read_line(timeout=1) == b"# SBDuino GPIO v2019.8.0"
        board.answer_lines(sb_arduino)
        status = read_lines_until(line_starts_with(b"+", b"-"))
        assert await link.exchange(b"R 2\n", status, timeout=1) == [b"# R 2", b"> H", b"+ OK"]
    assert link.stream.is_closed


async def test_a_large_write_waits_for_the_port_to_take_it(
    board: PtyBoard, stream: SerialStream
) -> None:
    # Nobody reads the board's end at first: the pty fills, then the transport's buffer
    # passes its 64 KiB high-water mark and the stream pauses. (With a reader running
    # from the start, whether the buffer ever filled depended on the machine's load.)
    chunk = bytes(range(256)) * 64  # 16 KiB
    sent = 0
    with anyio.fail_after(10):
        while not stream._write_paused:  # type: ignore[attr-defined]
            assert sent < 64, "64 writes of 16 KiB that nobody read never paused the port"
            await stream.send(chunk)
            sent += 1
        # One more write waits for the port to take what is queued.
        done = anyio.Event()

        async def send_one_more() -> None:
            await stream.send(chunk)
            sent_count[0] += 1
            done.set()

        sent_count = [sent]
        total = (sent + 1) * len(chunk)
        got = bytearray()
        stop = threading.Event()

        def reader() -> None:
            while not stop.is_set() and len(got) < total:
                try:
                    got.extend(os.read(board.master, 65536))
                except BlockingIOError:
                    stop.wait(0.002)

        thread = threading.Thread(target=reader, daemon=True)
        try:
            async with anyio.create_task_group() as group:
                group.start_soon(send_one_more)
                await anyio.sleep(0.05)
                assert not done.is_set(), "a write went out while the port's buffer was full"
                thread.start()
                await done.wait()
            await stream.aclose()  # waits for the output buffer to drain
            await anyio.to_thread.run_sync(thread.join, 5)
        finally:
            stop.set()
    assert sent_count[0] == sent + 1
    assert len(got) == total
    assert bytes(got) == chunk * (sent + 1)


async def test_the_port_vanishing_mid_exchange_raises_board_disconnection(
    board: PtyBoard, stream: SerialStream
) -> None:
    link = SerialLink(stream)

    async def unplug_soon() -> None:
        await anyio.sleep(0.02)
        board.unplug()

    with anyio.fail_after(2):
        async with anyio.create_task_group() as tg:
            tg.start_soon(unplug_soon)
            with pytest.raises(BoardDisconnectionError, match="gone away") as caught:
                await link.exchange(b"anyone?\n", read_line(), timeout=1)
    assert isinstance(caught.value.__cause__, serial.SerialException)
    with pytest.raises(BoardDisconnectionError, match="gone away"):
        await stream.send(b"x")
    stream.close_now()  # closing after a failure is quiet


async def test_close_now_is_synchronous_and_wakes_a_reader(
    board: PtyBoard, stream: SerialStream
) -> None:
    async def close_soon() -> None:
        await anyio.sleep(0.01)
        stream.close_now()

    with anyio.fail_after(1):
        async with anyio.create_task_group() as tg:
            tg.start_soon(close_soon)
            with pytest.raises(BoardDisconnectionError, match="closed"):
                await stream.receive()
    assert stream.is_closed and not stream.serial.is_open
    with pytest.raises(BoardDisconnectionError, match="closed"):
        await stream.send(b"x")
    stream.close_now()
    await stream.aclose()


def test_close_now_works_after_the_event_loop_has_gone(board: PtyBoard) -> None:
    """As in an ``atexit`` handler: no running loop, no executor."""

    async def open_it() -> SerialStream:
        return await open_serial_stream(board.path, 115200)

    opened = anyio.run(open_it)
    opened.close_now()
    assert not opened.serial.is_open


async def test_low_latency_failure_on_a_pty_is_only_logged(
    board: PtyBoard, caplog: pytest.LogCaptureFixture
) -> None:
    caplog.set_level(logging.DEBUG, logger="j5aio.backends.hardware.transports.serial_stream")
    opened = await open_serial_stream(board.path, 115200, low_latency=True)
    opened.close_now()
    if sys.platform.startswith("linux"):
        assert "could not set low-latency mode" in caplog.text


async def test_low_latency_is_asked_for_ftdi_ports_only(
    board: PtyBoard, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(sys, "platform", "linux")
    asked: list[bool] = []
    monkeypatch.setattr(
        serial.Serial, "set_low_latency_mode", lambda self, on: asked.append(on), raising=False
    )
    ftdi = PortInfo(board.path, vid=0x0403, pid=0x6001)
    monkeypatch.setattr("j5aio.backends.hardware.transports.discovery.find_port", lambda d: ftdi)
    (await open_serial_stream(board.path)).close_now()
    assert asked == [True]
    (await open_serial_stream(board.path, low_latency=False)).close_now()
    assert asked == [True]
    other = PortInfo(board.path, vid=0x1BDA, pid=0x0011)
    monkeypatch.setattr("j5aio.backends.hardware.transports.discovery.find_port", lambda d: other)
    (await open_serial_stream(board.path)).close_now()
    assert asked == [True]


def test_low_latency_helper_on_other_platforms(
    monkeypatch: pytest.MonkeyPatch, caplog: pytest.LogCaptureFixture
) -> None:
    caplog.set_level(logging.DEBUG, logger="j5aio.backends.hardware.transports.serial_stream")
    request = serial_stream_module._request_low_latency
    port = serial.serial_for_url("loop://", do_not_open=True)
    monkeypatch.setattr(sys, "platform", "darwin")
    request(port, "loop://", True)
    assert "only available on Linux" in caplog.text
    request(port, "loop://", None)  # auto: nothing to do off Linux
    monkeypatch.setattr(sys, "platform", "linux")
    request(port, "loop://", True)
    assert "has no low-latency mode" in caplog.text


def test_ftdi_detection_survives_a_failing_port_list(monkeypatch: pytest.MonkeyPatch) -> None:
    def broken(device: str) -> PortInfo | None:
        raise CommunicationError("no sysfs")

    monkeypatch.setattr("j5aio.backends.hardware.transports.discovery.find_port", broken)
    assert not serial_stream_module._is_ftdi("/dev/ttyUSB0")


async def test_a_failure_after_opening_closes_the_port(
    board: PtyBoard, monkeypatch: pytest.MonkeyPatch
) -> None:
    def explode(port: Any, url: str, low_latency: bool | None) -> None:
        raise RuntimeError("boom")

    monkeypatch.setattr(serial_stream_module, "_request_low_latency", explode)
    with pytest.raises(RuntimeError, match="boom"):
        await open_serial_stream(board.path)

    monkeypatch.undo()
    # Ports of earlier tests that the garbage collector finalises would call close too.
    gc.collect()
    closed: list[bool] = []
    original_close = serial.Serial.close

    def track_close(self: serial.Serial) -> None:
        if self.port == board.path:
            closed.append(True)
        original_close(self)

    async def attach_fails(self: Any) -> None:
        raise RuntimeError("attach failed")

    monkeypatch.setattr(serial.Serial, "close", track_close)
    monkeypatch.setattr(serial_stream_module._EventSerialStream, "_attach", attach_fails)
    with pytest.raises(RuntimeError, match="attach failed"):
        await open_serial_stream(board.path)
    assert closed == [True]


# -- opening errors ------------------------------------------------------------------------


async def test_a_missing_port_says_what_to_check(tmp_path: Any) -> None:
    missing = str(tmp_path / "ttyACM99")
    with pytest.raises(BoardDisconnectionError) as caught:
        await open_serial_stream(missing)
    message = str(caught.value)
    assert missing in message and "plugged in" in message
    assert isinstance(caught.value.__cause__, serial.SerialException)


@pytest.mark.parametrize(
    ("code", "kind", "text"),
    [
        (errno.ENOENT, BoardDisconnectionError, "no such port"),
        (errno.ENXIO, BoardDisconnectionError, "no such port"),
        (errno.EACCES, CommunicationError, "dialout"),
        (errno.EBUSY, CommunicationError, "in use"),
        (errno.EIO, CommunicationError, "Check that the board"),
    ],
)
async def test_open_errors_are_explained(
    monkeypatch: pytest.MonkeyPatch, code: int, kind: type[CommunicationError], text: str
) -> None:
    def failing_serial_for_url(url: str, *args: Any, **kwargs: Any) -> Any:
        raise serial.SerialException(code, f"could not open port {url}: [Errno {code}]")

    monkeypatch.setattr(serial, "serial_for_url", failing_serial_for_url)
    with pytest.raises(kind, match=text) as caught:
        await open_serial_stream("/dev/ttyACM7")
    assert "/dev/ttyACM7" in str(caught.value)


async def test_an_unknown_url_scheme_is_a_value_error() -> None:
    with pytest.raises(ValueError, match="not known"):
        await open_serial_stream("nonsense://here")


# -- pyserial URLs -------------------------------------------------------------------------


async def test_loop_url_is_polled() -> None:
    stream = await open_serial_stream("loop://", 115200, poll_interval=0.0005)
    link = SerialLink(stream)
    assert await link.exchange(b"echo me\n", read_line(), timeout=1) == b"echo me"
    assert type(stream).__name__ == "_PolledSerialStream"
    with pytest.raises(ValueError, match="max_bytes"):
        await stream.receive(0)
    await link.aclose()
    assert stream.is_closed and not stream.serial.is_open
    with pytest.raises(BoardDisconnectionError, match="closed"):
        await stream.receive()
    with pytest.raises(BoardDisconnectionError, match="closed"):
        await stream.send(b"x")


async def test_a_polled_port_that_fails_raises_board_disconnection() -> None:
    stream = await open_serial_stream("loop://", name="loopback")
    stream.serial.close()  # the handler fails underneath us
    with pytest.raises(BoardDisconnectionError, match="loopback: the port has gone away"):
        await stream.receive()
    with pytest.raises(BoardDisconnectionError, match="loopback: the port has gone away"):
        await stream.send(b"x")
    stream.close_now()


async def test_a_polled_port_retries_partial_writes(monkeypatch: pytest.MonkeyPatch) -> None:
    stream = await open_serial_stream("loop://", poll_interval=0.0005)
    writes: list[bytes] = []

    def write_two_bytes(data: Any) -> int:
        writes.append(bytes(data[:2]))
        return 2

    monkeypatch.setattr(stream.serial, "write", write_two_bytes)
    await stream.send(b"abcde")
    assert writes == [b"ab", b"cd", b"e"]
    stream.close_now()


async def test_socket_url_through_the_event_loop() -> None:
    async def echo(reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        while line := await reader.readline():
            writer.write(b"got " + line)
            await writer.drain()
        writer.close()

    server = await asyncio.start_server(echo, "127.0.0.1", 0)
    port = server.sockets[0].getsockname()[1]
    try:
        stream = await open_serial_stream(f"socket://127.0.0.1:{port}")
        async with SerialLink(stream) as link:
            assert await link.exchange(b"ping\n", read_line(), timeout=2) == b"got ping"
            assert link.name == f"socket://127.0.0.1:{port}"
    finally:
        server.close()
        await server.wait_closed()


def test_the_file_descriptor_probe() -> None:
    class NoFileno:
        pass

    class BrokenFileno:
        def fileno(self) -> int:
            raise OSError("not open")

    probe = serial_stream_module._has_file_descriptor
    assert not probe(NoFileno())
    assert not probe(BrokenFileno())
    with socket.socket() as sock:
        assert probe(sock)


# -- reading straight from the descriptor --------------------------------------------------


def count_library_reads(stream: SerialStream, monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """Count the calls of pyserial's ``read`` (the stream reads the descriptor itself)."""
    reads: list[int] = []
    library_read = stream.serial.read

    def counted(size: int = 1) -> bytes:
        reads.append(size)
        data: bytes = library_read(size)
        return data

    monkeypatch.setattr(stream.serial, "read", counted)
    return reads


class FakeOs:
    """``os`` for the stream module, with ``read`` and ``write`` replaced where given."""

    def __init__(
        self,
        read: Callable[[int, int], bytes] | None = None,
        write: Callable[[int, Any], int] | None = None,
    ) -> None:
        self._read = read
        self._write = write

    def __getattr__(self, name: str) -> Any:
        return getattr(os, name)

    def read(self, fd: int, size: int) -> bytes:
        return (self._read or os.read)(fd, size)

    def write(self, fd: int, data: Any) -> int:
        return (self._write or os.write)(fd, data)


class FullPort:
    """The stream's writes to a port with no room (EAGAIN) until ``full`` is cleared.

    Every write tried is kept in ``tried``; with ``broken`` set, writes fail (EIO).
    """

    def __init__(self, monkeypatch: pytest.MonkeyPatch) -> None:
        self.full = True
        self.broken = False
        self.tried: list[bytes] = []
        monkeypatch.setattr(serial_stream_module, "os", FakeOs(write=self._write))

    def _write(self, fd: int, data: Any) -> int:
        self.tried.append(bytes(data))
        if self.broken:
            raise OSError(errno.EIO, "Input/output error")
        if self.full:
            raise BlockingIOError(errno.EAGAIN, "no room")
        return os.write(fd, data)


async def test_received_bytes_are_read_straight_from_the_port(
    board: PtyBoard, stream: SerialStream, monkeypatch: pytest.MonkeyPatch
) -> None:
    reads = count_library_reads(stream, monkeypatch)
    board.write(b"one reply\n")
    with anyio.fail_after(2):
        assert await stream.receive() == b"one reply\n"
    assert reads == []  # one os.read, not pyserial's select and read


async def test_a_readable_port_with_nothing_to_read_is_nothing(
    board: PtyBoard, stream: SerialStream
) -> None:
    stream._on_readable()  # type: ignore[attr-defined]  # woken with nothing there (EAGAIN)
    assert not stream.is_closed and stream.serial.is_open
    board.write(b"later\n")
    with anyio.fail_after(2):
        assert await stream.receive() == b"later\n"
    assert stream.send_nowait(b"still open\n") is True


async def test_a_port_that_says_try_again_is_nothing(
    board: PtyBoard, stream: SerialStream, monkeypatch: pytest.MonkeyPatch
) -> None:
    def read(fd: int, size: int) -> bytes:
        raise BlockingIOError(errno.EAGAIN, "nothing yet")

    monkeypatch.setattr(serial_stream_module, "os", FakeOs(read=read))
    stream._on_readable()  # type: ignore[attr-defined]
    monkeypatch.undo()
    assert stream.serial.is_open
    board.write(b"then\n")
    with anyio.fail_after(2):
        assert await stream.receive() == b"then\n"


async def test_a_port_that_vanishes_ends_the_stream_and_is_closed(
    board: PtyBoard, stream: SerialStream
) -> None:
    board.unplug()  # reading the slave side now fails (EIO, or the end of the file)
    with anyio.fail_after(2), pytest.raises(BoardDisconnectionError, match="gone away") as caught:
        await stream.receive()
    assert isinstance(caught.value.__cause__, (OSError, serial.SerialException))
    assert not stream.serial.is_open  # closed at once, not left to the program's end
    with pytest.raises(BoardDisconnectionError, match="gone away"):
        stream.send_nowait(b"x")
    stream.close_now()  # still fine to close
    assert stream.is_closed


@pytest.mark.parametrize(
    "outcome", [b"", OSError(errno.EIO, "Input/output error")], ids=["end of file", "EIO"]
)
async def test_a_read_that_fails_or_ends_is_the_port_lost(
    board: PtyBoard,
    stream: SerialStream,
    monkeypatch: pytest.MonkeyPatch,
    outcome: bytes | OSError,
) -> None:
    def read(fd: int, size: int) -> bytes:
        if isinstance(outcome, OSError):
            raise outcome
        return outcome

    monkeypatch.setattr(serial_stream_module, "os", FakeOs(read=read))
    board.write(b"x")  # the port is readable: an empty read then is its end
    with anyio.fail_after(2), pytest.raises(BoardDisconnectionError, match="gone away") as caught:
        await stream.receive()
    if isinstance(outcome, OSError):
        assert caught.value.__cause__ is outcome
    else:
        assert isinstance(caught.value.__cause__, serial.SerialException)
        assert "no data" in str(caught.value.__cause__)
    assert not stream.serial.is_open


async def test_a_readiness_check_that_fails_is_the_port_lost(
    board: PtyBoard, stream: SerialStream, monkeypatch: pytest.MonkeyPatch
) -> None:
    failure = OSError(errno.EBADF, "Bad file descriptor")
    monkeypatch.setattr(serial_stream_module, "os", FakeOs(read=lambda fd, size: b""))
    monkeypatch.setattr(select, "select", _raise(failure))
    stream._on_readable()  # type: ignore[attr-defined]
    with anyio.fail_after(2), pytest.raises(BoardDisconnectionError, match="gone away") as caught:
        await stream.receive()
    assert caught.value.__cause__ is failure


# -- writing -------------------------------------------------------------------------------


async def test_what_the_port_takes_in_part_goes_on_when_it_has_room(
    board: PtyBoard, stream: SerialStream, monkeypatch: pytest.MonkeyPatch
) -> None:
    calls: list[bytes] = []

    def first_three_only(fd: int, data: Any) -> int:
        calls.append(bytes(data))
        if len(calls) == 1:
            return os.write(fd, bytes(data)[:3])
        return os.write(fd, data)

    monkeypatch.setattr(serial_stream_module, "os", FakeOs(write=first_three_only))
    assert stream.send_nowait(b"abcdef\n") is True
    assert calls == [b"abcdef\n"]  # the rest waits for the event loop's word
    assert await read_master_later(board, 7) == b"abcdef\n"
    assert calls[1] == b"def\n"


async def test_bytes_queued_for_the_port_go_out_before_later_ones(
    board: PtyBoard, stream: SerialStream, monkeypatch: pytest.MonkeyPatch
) -> None:
    port = FullPort(monkeypatch)
    direct = port.tried
    assert stream.send_nowait(b"first\n") is True  # no room: queued
    assert stream.send_nowait(b"second\n") is True  # behind it, not written ahead of it
    assert direct == [b"first\n"]
    port.full = False  # the port takes bytes again: the event loop writes the queue out
    assert await read_master_later(board, 13) == b"first\nsecond\n"
    assert direct[-1] == b"first\nsecond\n"
    assert stream.send_nowait(b"third\n") is True  # nothing queued now: straight out
    assert direct[-1] == b"third\n"
    assert read_master(board, 6) == b"third\n"


async def test_a_write_that_fails_raises_board_disconnection(
    board: PtyBoard, stream: SerialStream, monkeypatch: pytest.MonkeyPatch
) -> None:
    loop = asyncio.get_running_loop()
    reported: list[dict[str, Any]] = []
    loop.set_exception_handler(lambda _loop, context: reported.append(context))

    def refuse(fd: int, data: Any) -> int:
        raise OSError(errno.EIO, "Input/output error")

    monkeypatch.setattr(serial_stream_module, "os", FakeOs(write=refuse))
    try:
        with pytest.raises(BoardDisconnectionError, match="writing to the port failed"):
            await stream.send(b"x")
        with pytest.raises(BoardDisconnectionError, match="gone away"):
            await stream.receive()
    finally:
        loop.set_exception_handler(None)
    assert reported == []  # an unplugged board is not an event-loop error
    assert not stream.serial.is_open


async def test_a_queued_write_that_fails_wakes_the_waiting_sender(
    board: PtyBoard, stream: SerialStream, monkeypatch: pytest.MonkeyPatch
) -> None:
    port = FullPort(monkeypatch)
    chunk = b"x" * 40_000
    assert stream.send_nowait(chunk) is True
    assert stream.send_nowait(chunk) is True  # 80 kB queued: over the high-water mark
    assert stream.send_nowait(chunk) is False
    failed = anyio.Event()

    async def sender() -> None:
        with pytest.raises(BoardDisconnectionError, match="gone away"):
            await stream.send(chunk)
        failed.set()

    with anyio.fail_after(2):
        async with anyio.create_task_group() as group:
            group.start_soon(sender)
            await anyio.wait_all_tasks_blocked()
            assert not failed.is_set()
            port.broken = True  # the device goes while bytes wait for it
            await failed.wait()
    assert not stream.serial.is_open


async def test_send_now_goes_first_even_if_the_queue_cannot_be_stopped(
    board: PtyBoard,
    stream: SerialStream,
    monkeypatch: pytest.MonkeyPatch,
    caplog: pytest.LogCaptureFixture,
) -> None:
    caplog.set_level(logging.DEBUG, logger="j5aio.backends.hardware.transports.serial_stream")
    port = FullPort(monkeypatch)
    assert stream.send_nowait(b"queued\n") is True
    loop = asyncio.get_running_loop()
    fileno = stream.serial.fileno()
    monkeypatch.setattr(loop, "remove_writer", _raise(RuntimeError("the loop is going")))
    port.full = False
    stream.send_now(b"safe\n", 0.5)  # the queued request is dropped: the safe one goes
    assert "could not stop the queued writes" in caplog.text
    monkeypatch.undo()
    loop.remove_writer(fileno)
    assert read_master(board, 5) == b"safe\n"


async def test_a_full_port_woken_for_nothing_keeps_its_queue(
    board: PtyBoard, stream: SerialStream, monkeypatch: pytest.MonkeyPatch
) -> None:
    port = FullPort(monkeypatch)
    assert stream.send_nowait(b"kept\n") is True
    stream._on_writable()  # type: ignore[attr-defined]  # woken, but still no room
    assert stream.serial.is_open
    port.full = False
    assert await read_master_later(board, 5) == b"kept\n"


async def test_send_now_lets_a_waiting_sender_go_on(
    board: PtyBoard, stream: SerialStream, monkeypatch: pytest.MonkeyPatch
) -> None:
    port = FullPort(monkeypatch)
    chunk = b"x" * 70_000
    assert stream.send_nowait(chunk) is True  # over the high-water mark: senders wait
    assert stream.send_nowait(b"waits\n") is False
    sent = anyio.Event()

    async def sender() -> None:
        await stream.send(b"after\n")
        sent.set()

    with anyio.fail_after(2):
        async with anyio.create_task_group() as group:
            group.start_soon(sender)
            await anyio.wait_all_tasks_blocked()
            assert not sent.is_set()
            port.full = False
            stream.send_now(b"safe\n", 0.5)  # drops the queue: the sender may go on
            await sent.wait()
    assert await read_master_later(board, 11) == b"safe\nafter\n"


async def test_a_second_failure_keeps_the_first(stream: SerialStream) -> None:
    first = OSError(errno.EIO, "first")
    stream._lose(first)  # type: ignore[attr-defined]
    stream._lose(OSError(errno.ENODEV, "second"))  # type: ignore[attr-defined]
    with pytest.raises(BoardDisconnectionError, match="first") as caught:
        await stream.receive()
    assert caught.value.__cause__ is first


async def test_close_now_survives_errors_while_closing(
    stream: SerialStream, monkeypatch: pytest.MonkeyPatch, caplog: pytest.LogCaptureFixture
) -> None:
    caplog.set_level(logging.DEBUG, logger="j5aio.backends.hardware.transports.serial_stream")
    loop = asyncio.get_running_loop()

    def refuse(*args: Any) -> None:
        raise OSError("no")

    fileno = stream.serial.fileno()
    monkeypatch.setattr(loop, "remove_reader", refuse)
    monkeypatch.setattr(stream.serial, "close", refuse)
    stream.close_now()
    assert stream.is_closed
    assert "could not detach from the event loop" in caplog.text
    assert "error while closing the port" in caplog.text
    monkeypatch.undo()  # then clean up for real
    loop.remove_reader(fileno)
    stream.serial.close()


async def test_a_polled_receive_waits_for_data() -> None:
    stream = await open_serial_stream("loop://", poll_interval=0.001)
    async with anyio.create_task_group() as tg:

        async def send_later() -> None:
            await anyio.sleep(0.01)
            await stream.send(b"late")

        tg.start_soon(send_later)
        with anyio.fail_after(1):
            assert await stream.receive() == b"late"
    stream.close_now()


async def test_send_nowait_writes_at_once_unless_the_output_is_over_its_limit(
    board: PtyBoard, stream: SerialStream
) -> None:
    assert stream.send_nowait(b"now\n") is True
    assert read_master(board, 4) == b"now\n"
    stream._write_paused = True  # type: ignore[attr-defined]  # (as a full queue pauses it)
    assert stream.send_nowait(b"later\n") is False
    sender_done = anyio.Event()

    async def sender() -> None:
        await stream.send(b"later\n")
        sender_done.set()

    async with anyio.create_task_group() as group:
        group.start_soon(sender)
        await anyio.wait_all_tasks_blocked()
        assert not sender_done.is_set()  # waiting for the queue to go down
        stream._on_writable()  # type: ignore[attr-defined]  # the port has room: it goes on
    assert read_master(board, 6) == b"later\n"
    stream.close_now()
    with pytest.raises(BoardDisconnectionError):
        stream.send_nowait(b"gone\n")


# -- sending synchronously (the safety net) ------------------------------------------------


async def test_send_now_writes_at_once_through_a_pty(board: PtyBoard, stream: SerialStream) -> None:
    link = SerialLink(stream, name="pty")
    stream.send_now(b"first\n", 0.5)
    link.send_now(b"safe\n", timeout=0.5)
    assert link.is_dirty  # a reply it skipped must not be taken for another's
    assert read_master(board, len(b"first\nsafe\n")) == b"first\nsafe\n"


def test_send_now_works_after_the_event_loop_has_gone(board: PtyBoard) -> None:
    async def open_it() -> SerialStream:
        return await open_serial_stream(board.path, 115200)

    stream = anyio.run(open_it)
    stream.send_now(b"made safe\n", 0.5)
    stream.close_now()
    assert read_master(board, len(b"made safe\n")) == b"made safe\n"
    with pytest.raises(BoardDisconnectionError):
        stream.send_now(b"x", 0.5)


async def test_send_now_on_a_polled_port() -> None:
    stream = await open_serial_stream("loop://", poll_interval=0.0005)
    stream.send_now(b"echo\n", 0.5)
    assert await stream.receive() == b"echo\n"
    stream.close_now()
    with pytest.raises(BoardDisconnectionError, match="closed"):
        stream.send_now(b"x", 0.5)


async def test_send_now_gives_up_after_its_timeout(monkeypatch: pytest.MonkeyPatch) -> None:
    stream = await open_serial_stream("loop://", poll_interval=0.0005)
    monkeypatch.setattr(stream.serial, "write", lambda data: 0)
    with pytest.raises(CommunicationError, match=r"within 0\.01 s"):
        stream.send_now(b"never taken", 0.01)
    monkeypatch.setattr(stream.serial, "write", _raise(serial.SerialException("unplugged")))
    with pytest.raises(BoardDisconnectionError, match="writing to the port failed"):
        stream.send_now(b"x", 0.1)
    stream.close_now()


def read_master(board: PtyBoard, count: int) -> bytes:
    """Read what the program wrote to the port, straight from the master side."""
    data = b""
    deadline = time.monotonic() + 2
    while len(data) < count and time.monotonic() < deadline:
        try:
            data += os.read(board.master, 4096)
        except BlockingIOError:
            time.sleep(0.005)
    return data


async def read_master_later(board: PtyBoard, count: int) -> bytes:
    """Read what the program wrote to the port, letting the event loop write meanwhile."""
    data = b""
    with anyio.fail_after(2):
        while len(data) < count:
            await anyio.sleep(0.002)
            with contextlib.suppress(BlockingIOError):
                data += os.read(board.master, 4096)
    return data


def _raise(error: BaseException) -> Any:
    def fail(*args: Any) -> Any:
        raise error

    return fail

"""Serial ports as :class:`~.stream.ByteStream` objects, over pyserial.

:func:`open_serial_stream` opens a device path (``/dev/ttyACM0``, ``COM3``) or any pyserial
URL (``loop://``, ``socket://host:port``, ``rfc2217://...``). Ports with a file descriptor
(POSIX) are read and written by the event loop, which watches the descriptor; ports
without one (Windows, and URL handlers such as ``loop://`` and ``rfc2217://``) are polled
every ``poll_interval`` while a receive waits.

Closing never needs an executor:
:meth:`SerialStream.close_now <j5aio.backends.hardware.transports.stream.ByteStream.close_now>`
stops the event loop watching the port and closes it synchronously, so it also works inside
``atexit``.
"""

from __future__ import annotations

import asyncio
import errno
import functools
import logging
import os
import select
import sys
import time
from collections.abc import Coroutine
from typing import Any

import anyio
import anyio.lowlevel
import anyio.to_thread
import serial

from j5aio.errors import BoardDisconnectionError, CommunicationError

from ._inbox import Inbox
from .stream import ByteStream

__all__ = ["SerialStream", "open_serial_stream"]

_log = logging.getLogger(__name__)

_GONE = {errno.ENOENT, errno.ENODEV, errno.ENXIO}
_DENIED = {errno.EACCES, errno.EPERM}
_BUSY = {errno.EBUSY, errno.EAGAIN}
#: The most bytes read from a port at once (the board's replies are far shorter).
_READ_SIZE = 4096


class SerialStream(ByteStream):
    """A :class:`~.stream.ByteStream` over an open pyserial port.

    Made by :func:`open_serial_stream`.
    """

    def __init__(self, port: serial.SerialBase, name: str) -> None:
        self._port = port
        self._name = name
        self._closed = False

    @property
    def name(self) -> str:
        """The port's name (its path or URL, unless another name was given)."""
        return self._name

    @property
    def is_closed(self) -> bool:
        """Whether the stream has been closed from this side."""
        return self._closed

    @property
    def serial(self) -> serial.SerialBase:
        """The pyserial port object underneath (for settings such as DTR)."""
        return self._port

    def _closed_error(self) -> BoardDisconnectionError:
        return BoardDisconnectionError(f"{self._name}: the port is closed")

    def _write_now(self, data: bytes, timeout: float) -> None:
        """Write ``data`` to the port synchronously, waiting at most ``timeout`` seconds."""
        deadline = time.monotonic() + timeout
        remaining = memoryview(data)
        fileno = self._port.fileno() if _has_file_descriptor(self._port) else None
        while remaining:
            try:
                # os.write on the descriptor: pyserial's non-blocking write spins on EAGAIN.
                written = (
                    os.write(fileno, remaining)
                    if fileno is not None
                    else self._port.write(remaining)
                )
            except (BlockingIOError, InterruptedError):
                written = 0
            except (serial.SerialException, OSError) as exc:
                raise BoardDisconnectionError(
                    f"{self._name}: writing to the port failed ({exc})"
                ) from exc
            remaining = remaining[written or 0 :]
            left = deadline - time.monotonic()
            if not remaining:
                return
            if left <= 0:
                raise CommunicationError(
                    f"{self._name}: could not send {bytes(data)!r} within {timeout} s"
                )
            if fileno is not None:
                select.select([], [fileno], [], min(left, 0.01))
            else:
                time.sleep(min(left, 0.001))

    def _close_port(self) -> None:
        try:
            self._port.close()
        except Exception as exc:  # closing a vanished port may fail; it is closed anyway
            _log.debug("%s: error while closing the port: %r", self._name, exc)


#: Above this many bytes queued for the port, a sender waits (asyncio's transports'
#: default high-water mark); it goes on once the queue is down to the low-water mark.
_HIGH_WATER = 64 * 1024
_LOW_WATER = 16 * 1024
#: What a non-blocking descriptor raises when it has nothing to give, or no room.
_NOT_NOW = (BlockingIOError, InterruptedError)


class _EventSerialStream(SerialStream):
    """A port with a file descriptor, read and written when the event loop says it can be.

    The stream watches the (non-blocking) descriptor itself: received bytes are read
    with one ``os.read`` when the loop says there are some, and go to the inbox; a
    request is written with ``os.write`` at once, and what the port does not take goes
    to a queue that the loop writes out when the port has room. A sender waits while
    the queue is over its high-water mark. A failed read or write, or the end of the
    file of a vanished device, is the port lost: everything waiting on it gets a
    :class:`~j5aio.errors.BoardDisconnectionError`, and the port is closed. (pyserial's
    own non-blocking ``write`` retries a full port in a loop, which would hold the event
    loop for as long as a board does not read: the descriptor is written here instead.)
    """

    def __init__(self, port: serial.SerialBase, name: str) -> None:
        super().__init__(port, name)
        self._inbox = Inbox()
        self._write_paused = False
        self._writer_wakeup: anyio.Event | None = None
        self._lost = False
        self._loop: asyncio.AbstractEventLoop | None = None
        self._fileno = -1
        self._outgoing = bytearray()  # what the port has not taken yet, in order

    async def _attach(self) -> None:
        loop = asyncio.get_running_loop()
        # (pyserial opens POSIX ports non-blocking; its own reads and writes are told so.)
        self._port.timeout = 0
        self._port.write_timeout = 0
        self._fileno = self._port.fileno()
        loop.add_reader(self._fileno, self._on_readable)
        self._loop = loop

    async def send(self, data: bytes) -> None:
        """Queue ``data`` on the port; waits while the output buffer is over its limit.

        A cancelled caller sends nothing. Otherwise the bytes go out at once, with no
        turn of the event loop first: a request is on its way as soon as it can be, and
        a caller waiting for its reply yields then.
        """
        await anyio.lowlevel.checkpoint_if_cancelled()
        # This class's own (a subclass with a send of its own has the default back).
        while not _EventSerialStream.send_nowait(self, data):
            self._writer_wakeup = anyio.Event()
            await self._writer_wakeup.wait()

    def send_nowait(self, data: bytes) -> bool:
        """Queue ``data`` on the port unless its output buffer is over its limit.

        See :meth:`.ByteStream.send_nowait`: ``False`` (nothing sent) while the output
        buffer is over its limit.

        :raises BoardDisconnectionError: the port has gone or the stream is closed.
        """
        if self._closed or self._lost or self._loop is None:
            self._check_writable()  # raises, saying which
        if self._write_paused:
            return False
        outgoing = self._outgoing
        if outgoing:  # bytes queued ahead of these: they go after them
            outgoing += data
        else:
            try:
                written = os.write(self._fileno, data)
            except _NOT_NOW:
                written = 0
            except OSError as exc:
                self._lose(exc)
                raise BoardDisconnectionError(
                    f"{self._name}: writing to the port failed ({exc}); the device has gone "
                    "away. Check the USB cable and the board's power."
                ) from exc
            if written == len(data):
                return True
            outgoing += memoryview(data)[written:]
            assert self._loop is not None
            self._loop.add_writer(self._fileno, self._on_writable)
        if len(outgoing) > _HIGH_WATER:
            self._write_paused = True
        return True

    # The inbox's own coroutines, handed over rather than awaited in one of these: a
    # reply's wait is then one frame shorter, and so is its wake-up.

    def receive(self, max_bytes: int = 4096) -> Coroutine[Any, Any, bytes]:
        """Return received bytes; see :meth:`ByteStream.receive` (a coroutine)."""
        return self._inbox.take(max_bytes)

    def receive_by(
        self, deadline: float, max_bytes: int = 4096
    ) -> Coroutine[Any, Any, bytes | None]:
        """Return received bytes, or ``None`` at ``deadline`` (a coroutine).

        See :meth:`.ByteStream.receive_by`.
        """
        return self._inbox.take_by(max_bytes, deadline)

    def send_now(self, data: bytes, timeout: float) -> None:
        """Drop output still queued, then write ``data`` synchronously; see :class:`ByteStream`."""
        self._check_writable()
        self._drop_outgoing()  # queued output would otherwise follow ``data``
        self._write_now(bytes(data), timeout)

    def close_now(self) -> None:
        """Stop watching the port and close it, synchronously; idempotent."""
        if self._closed:
            return
        self._closed = True
        self._inbox.finish(self._closed_error(), discard=True)
        self._wake_writer()
        self._detach()
        self._close_port()

    async def aclose(self, *, flush_timeout: float = 0.5) -> None:
        """Let queued output go (for at most ``flush_timeout`` seconds), then close."""
        with anyio.CancelScope(shield=True), anyio.move_on_after(flush_timeout):
            # Polled: this only runs while the device is not taking bytes.
            while not self._closed and not self._lost and self._outgoing:  # noqa: ASYNC110
                await anyio.sleep(0.001)
        self.close_now()
        await anyio.lowlevel.checkpoint()

    def _on_readable(self) -> None:
        """The event loop's call when the port has bytes (or has failed)."""
        data = self._read_some()
        if data == b"":
            # pyserial sets the port to return at once (VMIN 0), so an empty read is either
            # a wake-up with nothing after all or the end of a vanished device's file. As
            # pyserial's own read decides: readable now and still empty is the end.
            try:
                readable, _, _ = select.select([self._fileno], [], [], 0)
            except (OSError, ValueError) as exc:
                self._lose(exc)
                return
            if not readable:
                return
            data = self._read_some()
            if data == b"":
                self._lose(
                    serial.SerialException(
                        "the device reports readiness to read but returned no data"
                    )
                )
                return
        if data:
            self._inbox.feed(data)

    def _read_some(self) -> bytes | None:
        """What the port has (``b""``: nothing, or its end), or ``None`` once it has failed."""
        try:
            return os.read(self._fileno, _READ_SIZE)
        except _NOT_NOW:
            return b""
        except OSError as exc:
            self._lose(exc)
            return None

    def _on_writable(self) -> None:
        """The event loop's call when the port has room for queued bytes."""
        outgoing = self._outgoing
        try:
            written = os.write(self._fileno, outgoing)
        except _NOT_NOW:
            return
        except OSError as exc:
            self._lose(exc)
            return
        del outgoing[:written]
        if not outgoing and self._loop is not None:
            self._loop.remove_writer(self._fileno)
        if self._write_paused and len(outgoing) <= _LOW_WATER:
            self._write_paused = False
            self._wake_writer()

    def _detach(self) -> None:
        """Stop the event loop watching the port, and drop what it has not taken."""
        loop, self._loop = self._loop, None
        self._outgoing.clear()
        if loop is None:
            return
        try:
            loop.remove_reader(self._fileno)
            loop.remove_writer(self._fileno)
        except Exception as exc:  # (a closed event loop has no watchers left to remove)
            _log.debug("%s: could not detach from the event loop: %r", self._name, exc)

    def _drop_outgoing(self) -> None:
        """Forget what the port has not taken (the safety net's write goes first)."""
        self._outgoing.clear()
        if self._loop is not None:
            try:
                self._loop.remove_writer(self._fileno)
            except Exception as exc:  # (the safety net's write must not fail for this)
                _log.debug("%s: could not stop the queued writes: %r", self._name, exc)
        if self._write_paused:
            self._write_paused = False
            self._wake_writer()

    def _lose(self, exc: BaseException) -> None:
        """The port failed: tell everyone waiting, stop watching it and close it."""
        if self._lost or self._closed:
            return
        _log.debug("%s: the port failed: %r", self._name, exc)
        self._detach()
        self._port_lost(exc)
        self._close_port()

    def _check_writable(self) -> None:
        if self._closed:
            raise self._closed_error()
        if self._lost or self._loop is None:
            raise BoardDisconnectionError(
                f"{self._name}: the port has gone away. Check the USB cable and the board's "
                "power, then run the program again."
            )

    def _port_lost(self, exc: BaseException) -> None:
        self._lost = True
        error = BoardDisconnectionError(
            f"{self._name}: the port has gone away ({exc}). Check the USB cable and "
            "the board's power, then run the program again."
        )
        error.__cause__ = exc
        self._inbox.finish(error)
        self._wake_writer()

    def _wake_writer(self) -> None:
        if self._writer_wakeup is not None:
            self._writer_wakeup.set()


class _PolledSerialStream(SerialStream):
    """A pyserial URL handler with no file descriptor, polled while waiting."""

    def __init__(self, port: serial.SerialBase, name: str, poll_interval: float) -> None:
        super().__init__(port, name)
        self._poll_interval = poll_interval
        port.timeout = 0

    async def send(self, data: bytes) -> None:
        """Write ``data`` to the port."""
        await anyio.lowlevel.checkpoint()
        remaining = memoryview(data)
        while remaining:
            self._check_open()
            try:
                written = self._port.write(remaining)
            except (serial.SerialException, OSError) as exc:
                raise self._gone(exc) from exc
            remaining = remaining[written or 0 :]
            if remaining:
                await anyio.sleep(self._poll_interval)

    async def receive(self, max_bytes: int = 4096) -> bytes:
        """Return received bytes, polling until some arrive; see :meth:`ByteStream.receive`."""
        if max_bytes < 1:
            raise ValueError(f"max_bytes must be at least 1, not {max_bytes}")
        await anyio.lowlevel.checkpoint()
        while True:
            self._check_open()
            try:
                data: bytes = self._port.read(max_bytes)
            except (serial.SerialException, OSError) as exc:
                raise self._gone(exc) from exc
            if data:
                return data
            await anyio.sleep(self._poll_interval)

    def send_now(self, data: bytes, timeout: float) -> None:
        """Write ``data`` synchronously; see :meth:`ByteStream.send_now`."""
        self._check_open()
        self._write_now(bytes(data), timeout)

    def close_now(self) -> None:
        """Close the port, synchronously; idempotent."""
        if not self._closed:
            self._closed = True
            self._close_port()

    def _check_open(self) -> None:
        if self._closed:
            raise self._closed_error()

    def _gone(self, exc: BaseException) -> BoardDisconnectionError:
        return BoardDisconnectionError(f"{self._name}: the port has gone away ({exc})")


def _open_error(url: str, exc: BaseException) -> CommunicationError:
    code = getattr(exc, "errno", None)
    if code in _GONE:
        return BoardDisconnectionError(
            f"Could not open {url}: there is no such port. Check that the board is plugged "
            "in and powered, and that the port name is right (`python -m "
            "serial.tools.list_ports -v` lists the ports)."
        )
    if code in _DENIED:
        return CommunicationError(
            f"Could not open {url}: permission denied. On Linux, add yourself to the group "
            "that owns the port (usually `dialout`: `sudo usermod -aG dialout $USER`, then "
            "log out and in again)."
        )
    if code in _BUSY:
        return CommunicationError(
            f"Could not open {url}: the port is in use. Close any other program (or robot) "
            "using it and try again."
        )
    return CommunicationError(
        f"Could not open {url}: {exc}. Check that the board is plugged in and powered."
    )


def _is_ftdi(device: str) -> bool:
    from .discovery import find_port

    try:
        port = find_port(device)
    except CommunicationError:
        return False
    return port is not None and port.is_ftdi


def _request_low_latency(port: serial.SerialBase, url: str, low_latency: bool | None) -> None:
    """Ask for the ASYNC_LOW_LATENCY flag where it applies; failure is only logged."""
    if low_latency is False:
        return
    if not sys.platform.startswith("linux"):
        if low_latency:
            _log.debug("%s: low-latency mode is only available on Linux", url)
        return
    if low_latency is None and not _is_ftdi(url):
        return
    setter = getattr(port, "set_low_latency_mode", None)
    if setter is None:
        _log.debug("%s: this kind of port has no low-latency mode", url)
        return
    try:
        setter(True)
    except (ValueError, OSError, NotImplementedError) as exc:
        _log.debug("%s: could not set low-latency mode: %s", url, exc)
    else:
        _log.debug("%s: low-latency mode on", url)


def _open_port(
    url: str, baudrate: int, low_latency: bool | None, options: dict[str, Any]
) -> serial.SerialBase:
    """Open the port (blocking; runs in a worker thread)."""
    try:
        port: serial.SerialBase = serial.serial_for_url(
            url, baudrate=baudrate, do_not_open=True, **options
        )
        port.open()
    except (serial.SerialException, OSError) as exc:
        raise _open_error(url, exc) from exc
    try:
        _request_low_latency(port, url, low_latency)
    except BaseException:
        port.close()
        raise
    return port


def _has_file_descriptor(port: serial.SerialBase) -> bool:
    fileno = getattr(port, "fileno", None)
    if fileno is None:
        return False
    try:
        fileno()
    except (OSError, ValueError, AttributeError, NotImplementedError):
        return False
    return True


async def open_serial_stream(
    url_or_path: str,
    baudrate: int = 115200,
    *,
    name: str | None = None,
    low_latency: bool | None = None,
    poll_interval: float = 0.001,
    **serial_options: Any,
) -> SerialStream:
    """Open a serial port (or pyserial URL) as a :class:`~.stream.ByteStream`.

    :param url_or_path: a device path such as ``/dev/ttyACM0`` or ``COM3``, or a pyserial
        URL such as ``loop://`` or ``socket://localhost:9000``.
    :param baudrate: the line speed (ignored by USB CDC boards).
    :param name: the name for errors and the wire log; defaults to ``url_or_path``.
    :param low_latency: ask Linux for the ASYNC_LOW_LATENCY flag: ``None`` (the
        default) asks only for FTDI adapters, ``True`` always, ``False`` never. Where
        the platform refuses, this is logged at DEBUG and ignored.
    :param poll_interval: how often a URL handler without a file descriptor is polled
        while a receive waits, in seconds.
    :param serial_options: passed on to ``serial.serial_for_url`` (``bytesize``,
        ``parity``, ``rtscts``, ``exclusive``, ...).
    :raises BoardDisconnectionError: there is no such port.
    :raises CommunicationError: the port exists but could not be opened (permission,
        in use, ...); the message says what to check.
    :raises ValueError: the URL or a setting is invalid.
    """
    opener = functools.partial(_open_port, url_or_path, baudrate, low_latency, serial_options)
    port = await anyio.to_thread.run_sync(opener)
    label = name if name is not None else url_or_path
    stream: SerialStream
    try:
        if _has_file_descriptor(port):
            event_stream = _EventSerialStream(port, label)
            await event_stream._attach()
            stream = event_stream
        else:
            stream = _PolledSerialStream(port, label, poll_interval)
        await anyio.lowlevel.checkpoint()
    except BaseException:
        port.close()
        raise
    return stream

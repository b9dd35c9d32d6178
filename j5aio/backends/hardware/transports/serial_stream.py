"""Serial ports as :class:`~.stream.ByteStream` objects, over pyserial-asyncio-fast.

:func:`open_serial_stream` opens a device path (``/dev/ttyACM0``, ``COM3``) or any pyserial
URL (``loop://``, ``socket://host:port``, ``rfc2217://...``). Ports with a file descriptor
are driven by the event loop through pyserial-asyncio-fast's transport; URL handlers
without one (``loop://``, ``rfc2217://``) are polled every ``poll_interval`` while a
receive waits.

Closing never needs an executor:
:meth:`SerialStream.close_now <j5aio.backends.hardware.transports.stream.ByteStream.close_now>`
stops the event loop watching the port and closes it synchronously, so it also works inside
``atexit`` (the library's own ``close()`` closes through an executor, which fails at interpreter
exit).

pyserial-asyncio-fast needs the asyncio event loop (it is how j5aio runs); on Windows it
polls the port every half millisecond.
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
from collections.abc import Callable, Coroutine
from typing import Any

import anyio
import anyio.lowlevel
import anyio.to_thread
import serial
import serial_asyncio_fast

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


class _SerialProtocol(asyncio.Protocol):
    """Feeds received bytes and the loss of the port to an :class:`_EventSerialStream`."""

    def __init__(self, stream: _EventSerialStream) -> None:
        self._stream = stream

    def data_received(self, data: bytes) -> None:
        self._stream._inbox.feed(data)

    def connection_lost(self, exc: Exception | None) -> None:
        self._stream._port_lost(exc)

    def pause_writing(self) -> None:
        self._stream._write_paused = True

    def resume_writing(self) -> None:
        self._stream._write_paused = False
        self._stream._wake_writer()


class _QuietSerialTransport(serial_asyncio_fast.SerialTransport):
    """pyserial-asyncio-fast's transport: received bytes read at once, quiet when unplugged.

    **Reading.** When the event loop says the port is readable, the library reads it
    through pyserial, whose ``read`` is made for blocking use: it asks ``select`` again
    whether there is anything to read, then reads. Here the bytes are read straight from
    the (non-blocking) descriptor and handed to ``deliver``: a system call, where
    pyserial's read makes two and runs a dozen lines of Python more, on the path of
    every reply. Only bytes are taken this way. Anything else (nothing there after all,
    an error, the end of the file of a vanished device) goes to the library's own read,
    which meets it as it always has: nothing to read is nothing, and a failure closes
    the transport with pyserial's ``SerialException``. (Should the library stop calling
    this hook, its own read runs: nothing else changes.)

    **Failures.** The library reports a failed write to the event loop's exception
    handler, which prints a traceback ("Fatal write error on serial transport") for what
    is only a board being unplugged. The stream raises
    :class:`~j5aio.errors.BoardDisconnectionError` for it, which says what to check; here
    the failure is logged at DEBUG level instead, and the transport closed as before.
    (Should the library stop calling this hook, the traceback is printed again: nothing
    else changes.)
    """

    def __init__(
        self,
        loop: asyncio.AbstractEventLoop,
        protocol: asyncio.Protocol,
        port: serial.SerialBase,
        deliver: Callable[[bytes], None],
    ) -> None:
        super().__init__(loop, protocol, port)
        self._deliver = deliver
        self._descriptor = port.fileno()

    def _read_ready(self) -> None:
        try:
            data = os.read(self._descriptor, _READ_SIZE)
        except OSError:
            data = b""
        if data:
            self._deliver(data)
        else:  # nothing after all, or a failure: the library's read tells which
            super()._read_ready()

    def _fatal_error(
        self, exc: BaseException, message: str = "Fatal error on serial transport"
    ) -> None:
        abort = getattr(self, "_abort", None)
        if not isinstance(exc, serial.SerialException) or abort is None:
            super()._fatal_error(exc, message)
            return
        _log.debug("%s: %s: %r", getattr(self.serial, "port", "?"), message, exc)
        abort(exc)


class _EventSerialStream(SerialStream):
    """A port with a file descriptor, watched by the event loop."""

    def __init__(self, port: serial.SerialBase, name: str) -> None:
        super().__init__(port, name)
        self._inbox = Inbox()
        self._write_paused = False
        self._writer_wakeup: anyio.Event | None = None
        self._lost = False
        self._transport: serial_asyncio_fast.SerialTransport | None = None
        self._fileno = -1
        # Whether bytes have been handed to the transport (which queues what the port
        # does not take) since its buffer was last seen empty: only then is it asked.
        self._handed_over = False

    async def _attach(self) -> None:
        loop = asyncio.get_running_loop()
        # (What the library's connection_for_serial does, with the quieter transport.)
        self._transport = _QuietSerialTransport(
            loop, _SerialProtocol(self), self._port, self._inbox.feed
        )
        self._fileno = self._port.fileno()

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
        transport = self._transport
        if self._closed or self._lost or transport is None or transport.is_closing():
            self._check_writable()  # raises, saying which
        assert transport is not None
        if self._write_paused:
            return False
        if not self._handed_over or not transport.get_write_buffer_size():
            # Nothing queued ahead of it: the bytes go straight to the port, as the
            # transport's write would (after five calls of its own and pyserial's).
            # What the port does not take at once, or refuses, goes to the transport,
            # which queues it, or meets the error its own way.
            self._handed_over = False
            try:
                written = os.write(self._fileno, data)
            except OSError:
                written = 0
            if written == len(data):
                return True
            data = data[written:]
        self._handed_over = True  # the transport may hold bytes now: ask it next time
        transport.write(data)
        if transport.is_closing():
            raise BoardDisconnectionError(
                f"{self._name}: writing to the port failed; the device has gone away. "
                "Check the USB cable and the board's power."
            )
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
        assert self._transport is not None
        self._transport.flush()  # queued output would otherwise follow ``data``
        self._write_now(bytes(data), timeout)

    def close_now(self) -> None:
        """Stop watching the port and close it, synchronously; idempotent."""
        if self._closed:
            return
        self._closed = True
        self._inbox.finish(self._closed_error(), discard=True)
        self._wake_writer()
        transport = self._transport
        if transport is not None and transport.is_closing():
            return  # the transport is already closing the port after a failure
        if transport is not None:
            try:
                transport.pause_reading()  # removes the reader from the event loop
                transport.flush()  # removes the writer and drops unsent bytes
            except Exception as exc:
                _log.debug("%s: could not detach from the event loop: %r", self._name, exc)
        self._close_port()

    async def aclose(self, *, flush_timeout: float = 0.5) -> None:
        """Let queued output go (for at most ``flush_timeout`` seconds), then close."""
        with anyio.CancelScope(shield=True), anyio.move_on_after(flush_timeout):
            # The transport gives no event for "buffer empty", only for the high-water
            # mark, so poll; this only runs while the device is not taking bytes.
            while (  # noqa: ASYNC110
                not self._closed
                and not self._lost
                and self._transport is not None
                and self._transport.get_write_buffer_size() > 0
            ):
                await anyio.sleep(0.001)
        self.close_now()
        await anyio.lowlevel.checkpoint()

    def _check_writable(self) -> None:
        if self._closed:
            raise self._closed_error()
        if self._lost or self._transport is None or self._transport.is_closing():
            raise BoardDisconnectionError(
                f"{self._name}: the port has gone away. Check the USB cable and the board's "
                "power, then run the program again."
            )

    def _port_lost(self, exc: Exception | None) -> None:
        self._lost = True
        if exc is None:
            error = self._closed_error()
        else:
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

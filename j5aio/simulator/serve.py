"""Serving a board simulator on a pseudo-terminal, so that any program can open it.

:func:`serve_on_pty` makes a pseudo-terminal pair and drives its master side with a
simulator (anything shaped like
:class:`~j5aio.backends.hardware.transports.memory.SerialSimulatorLike`): bytes a program
writes to the slave side go to ``simulator.receive`` and the simulator's answers are
written back. The slave side's path (``/dev/pts/N``) can be opened as a serial port by
pyserial, by j5, by ``screen`` or by any other program::

    with serve_on_pty(SBArduinoSimulator()) as server:
        port = serial.Serial(server.path, 115200, timeout=1)

Opening the slave side resets the simulated board, as opening a real Arduino's port does:
each time a program opens the port, ``simulator.open()`` is called and the boot output it
returns is written ``boot_delay * time_scale`` seconds later (and never sooner than
:data:`OPEN_SETTLE_TIME`, so that the opening program's input flush cannot eat it).

**Unplugging.** While the simulator is unplugged (``simulator.unplug()``) the server
closes the pseudo-terminal, so a program that has the port open gets an error, as from a
real board whose cable came out; when it is plugged back in, a new pseudo-terminal is
made. Its path differs (``/dev/pts/M``), so give the server a ``link``: a symbolic link
kept pointing at the current pseudo-terminal (and removed when the server closes), which
programs open as the board's port, before and after a replug, and across restarts of
``python -m j5aio simulate NAME --pty --link PATH``.

The pseudo-terminal is in raw mode (no echo, no line editing, no CR/LF translation). The
server runs in a thread of its own, so it works beside synchronous and asynchronous code
alike; only that thread touches the simulator while the server runs.

For an in-process, in-memory connection use
:class:`~j5aio.backends.hardware.transports.memory.SimulatorStream` instead.

Pseudo-terminals exist on POSIX systems only.
"""

from __future__ import annotations

import contextlib
import errno
import logging
import math
import os
import select
import threading
import time
import tty
from collections import deque
from types import TracebackType
from typing import Self

from j5aio.backends.hardware.transports.memory import SerialSimulatorLike

from .clock import Clock, drive, kit_clock

__all__ = ["OPEN_SETTLE_TIME", "PtyServer", "reply_due", "serve_on_pty"]

LOGGER = logging.getLogger(__name__)

#: The least time, in seconds, between a program opening the port and the boot output.
OPEN_SETTLE_TIME = 0.05

#: How often, in seconds, the server looks whether a program has opened the port.
_IDLE_POLL_INTERVAL = 0.01

#: The longest wait of the server thread with nothing due, in seconds.
_IDLE_WAIT = 0.1

#: Descriptors below this number can be waited on with ``select`` (its ``FD_SETSIZE``).
_SELECT_LIMIT = 1024

_NOTHING_TO_READ = frozenset({errno.EAGAIN, errno.EWOULDBLOCK, errno.EIO})


class PtyServer:
    """A simulator served on a pseudo-terminal; made and started by :func:`serve_on_pty`.

    Use it as a context manager (sync or async), or call :meth:`close` when done.

    :param simulator: the simulated board to serve.
    :param time_scale: multiplies the simulator's boot delay; ``0`` makes it (almost)
        instant.
    :param uart_timing: if true, each reply comes out only after the time the board's
        UART would take to receive the request and send the reply (10 bits a byte at the
        simulator's baud rate), as on the real wire.
    :param link: a path to keep as a symbolic link to the current pseudo-terminal;
        an existing symbolic link there is replaced, anything else is refused.
    :param clock: the clock the board's firmware timers (a note, a flashing LED) follow
        from now on; by default real time divided by ``time_scale``
        (:func:`~j5aio.simulator.clock.kit_clock`). A board without timers ignores it.
    :raises FileExistsError: ``link`` exists and is not a symbolic link.
    """

    def __init__(
        self,
        simulator: SerialSimulatorLike,
        *,
        time_scale: float = 1.0,
        uart_timing: bool = False,
        link: str | os.PathLike[str] | None = None,
        clock: Clock | None = None,
    ) -> None:
        if time_scale < 0:
            raise ValueError(f"time_scale must be zero or more, not {time_scale}")
        drive([simulator], clock if clock is not None else kit_clock(time_scale))
        self._link = os.fspath(link) if link is not None else None
        link_path = self._link
        if link_path is not None and os.path.lexists(link_path) and not os.path.islink(link_path):
            raise FileExistsError(
                f"{link_path} exists and is not a symbolic link; choose another path"
            )
        self._simulator = simulator
        self._time_scale = time_scale
        self._seconds_per_byte = 10 / simulator.baudrate if uart_timing else 0.0
        self._master = -1
        self._path = ""
        self._open_pty()
        self._wake_read, self._wake_write = os.pipe()
        self._pending: deque[tuple[float, bytes]] = deque()
        self._port_open = False
        self._opened_count = 0
        self._stopping = False
        self._closed = False
        self._thread = threading.Thread(
            target=self._run, name=f"pty server {self._path}", daemon=True
        )

    @property
    def path(self) -> str:
        """The path of the slave side, to open as a serial port (e.g. ``/dev/pts/4``).

        It changes each time the board is plugged back in; :attr:`link` does not.
        """
        return self._path

    @property
    def has_pty(self) -> bool:
        """Whether the pseudo-terminal exists now (not while the board is unplugged)."""
        return self._master >= 0

    @property
    def link(self) -> str | None:
        """The symbolic link kept pointing at :attr:`path`, if one was asked for."""
        return self._link

    @property
    def port(self) -> str:
        """The path to open as the board's port: :attr:`link` if there is one."""
        return self._link if self._link is not None else self._path

    @property
    def simulator(self) -> SerialSimulatorLike:
        """The simulated board being served."""
        return self._simulator

    @property
    def opened_count(self) -> int:
        """How many times a program has opened the port so far."""
        return self._opened_count

    @property
    def is_port_open(self) -> bool:
        """Whether a program has the port open now."""
        return self._port_open

    @property
    def is_serving(self) -> bool:
        """Whether the server thread is running."""
        return self._thread.is_alive()

    def start(self) -> None:
        """Start serving in a background thread.

        :raises RuntimeError: the server was started before, or is closed.
        """
        if self._closed:
            raise RuntimeError(f"the server on {self._path} is closed; make a new one")
        self._thread.start()

    def close(self, timeout: float = 5.0) -> None:
        """Stop serving and release the pseudo-terminal; idempotent.

        A program that still has the port open then reads end of file or gets an error.

        :param timeout: the longest time to wait for the server thread to stop, in seconds.
        """
        if self._closed:
            return
        self._closed = True
        self._stopping = True
        with contextlib.suppress(OSError):
            os.write(self._wake_write, b"x")
        if self._thread.is_alive():
            self._thread.join(timeout)
        for fd in (self._master, self._wake_read, self._wake_write):
            if fd >= 0:
                with contextlib.suppress(OSError):
                    os.close(fd)
        if self._link is not None and os.path.islink(self._link):
            with contextlib.suppress(OSError):
                os.unlink(self._link)

    def __enter__(self) -> Self:
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self.close()

    async def __aenter__(self) -> Self:
        return self

    async def __aexit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self.close()

    def __repr__(self) -> str:
        state = "serving" if self.is_serving else "stopped"
        return f"<PtyServer {type(self._simulator).__name__} on {self._path} {state}>"

    # The pseudo-terminal.

    def _open_pty(self) -> None:
        master, slave = os.openpty()
        tty.setraw(slave)
        self._path = os.ttyname(slave)
        # With the slave closed here, the master reports a hang-up until a program opens
        # the path: that is how an "open" (a board reset) is noticed.
        os.close(slave)
        os.set_blocking(master, False)
        self._master = master
        if self._link is not None:
            temporary = f"{self._link}.{os.getpid()}.tmp"
            with contextlib.suppress(FileNotFoundError):
                os.unlink(temporary)
            os.symlink(self._path, temporary)
            os.replace(temporary, self._link)  # atomic: never a moment without the link

    def _unplugged(self, poller: select.poll) -> None:
        """Close the pseudo-terminal: the program with the port open gets an error."""
        poller.unregister(self._master)
        os.close(self._master)
        self._master = -1
        self._port_open = False
        self._pending.clear()
        LOGGER.info("the simulated board on %s was unplugged", self._path)

    # The server thread.

    def _run(self) -> None:
        poller = select.poll()
        poller.register(self._wake_read, select.POLLIN)
        poller.register(self._master, select.POLLIN)
        while not self._stopping:
            try:
                self._step(poller)
            except Exception:  # a simulator bug must not kill the port silently
                LOGGER.exception("the simulator on %s failed; still serving", self._path)

    def _step(self, poller: select.poll) -> None:
        if not self._simulator.connected:
            if self._master >= 0:
                self._unplugged(poller)
            self._sleep(_IDLE_POLL_INTERVAL)
            return
        if self._master < 0:
            self._open_pty()
            poller.register(self._master, select.POLLIN)
        hung_up = self._master_hung_up()
        if hung_up:
            if self._port_open:
                self._port_open = False
                self._pending.clear()
            self._sleep(_IDLE_POLL_INTERVAL)
            return
        if not self._port_open:
            self._port_opened()
        if self._wait_for_input(poller):
            self._read_master()
        self._write_due()

    def _wait_for_input(self, poller: select.poll) -> bool:
        """Wait until input comes, output is due or close() is called; True if input came.

        ``select`` waits to the microsecond, so a reply goes out when it is due rather than
        at the next whole millisecond (``poll`` and ``epoll`` round their timeouts up to
        milliseconds). Descriptors beyond ``select``'s limit fall back to ``poll``.
        """
        writing = self._due()
        timeout = self._wait_time()
        if max(self._master, self._wake_read) < _SELECT_LIMIT:
            readable, _, _ = select.select(
                [self._master, self._wake_read], [self._master] if writing else [], [], timeout
            )
            return self._master in readable
        poller.modify(self._master, select.POLLIN | (select.POLLOUT if writing else 0))
        events = dict(poller.poll(math.ceil(timeout * 1000)))
        return bool(events.get(self._master, 0) & select.POLLIN)

    def _master_hung_up(self) -> bool:
        probe = select.poll()
        probe.register(self._master, select.POLLIN)
        events = dict(probe.poll(0)).get(self._master, 0)
        return bool(events & select.POLLHUP) and not events & select.POLLIN

    def _sleep(self, seconds: float) -> None:
        # Wait, but wake at once when close() is called.
        select.select([self._wake_read], [], [], seconds)

    def _port_opened(self) -> None:
        self._port_open = True
        self._opened_count += 1
        self._pending.clear()
        boot = self._simulator.open()
        delay = max(OPEN_SETTLE_TIME, self._simulator.boot_delay * self._time_scale)
        if boot:
            self._pending.append((time.monotonic() + delay, boot))

    def _read_master(self) -> None:
        try:
            data = os.read(self._master, 4096)
        except OSError as error:
            # EAGAIN: nothing after all; EIO: the program closed the port meanwhile.
            if error.errno in _NOTHING_TO_READ:
                return
            raise  # pragma: no cover - an unexpected failure, logged by _run
        if not data or not self._simulator.connected:
            return
        arrived = time.monotonic() + len(data) * self._seconds_per_byte
        response = self._simulator.receive(data)
        if response:
            due = reply_due(
                arrived,
                len(response) * self._seconds_per_byte,
                self._pending[-1][0] if self._pending else 0.0,
            )
            self._pending.append((due, response))

    def _due(self) -> bool:
        return bool(self._pending) and self._pending[0][0] <= time.monotonic()

    def _wait_time(self) -> float:
        """Seconds until the next output is due, at most :data:`_IDLE_WAIT`."""
        if not self._pending:
            return _IDLE_WAIT
        return max(0.0, min(_IDLE_WAIT, self._pending[0][0] - time.monotonic()))

    def _write_due(self) -> None:
        while self._due():
            due, chunk = self._pending.popleft()
            try:
                written = os.write(self._master, chunk)
            except BlockingIOError:  # the program is not reading: wait until it does
                written = 0
            except OSError as error:  # pragma: no cover - EIO: the port closed (not Linux)
                if error.errno != errno.EIO:
                    raise
                self._pending.clear()
                return
            if written < len(chunk):
                self._pending.appendleft((due, chunk[written:]))
                return


def reply_due(arrived: float, sending_time: float, line_free_at: float) -> float:
    """Return when the last byte of a reply reaches the program, as on a real UART.

    The board answers once the request has reached it (``arrived``: the time it was
    written plus its own time on the wire); the reply then takes ``sending_time`` on the
    wire, starting no sooner than the board's transmit line is free of earlier output
    (``line_free_at``; the boot banner, an earlier reply), which it never overtakes. A
    board without UART timing has zero times, so it answers at once.
    """
    return max(arrived, line_free_at) + sending_time


def serve_on_pty(
    simulator: SerialSimulatorLike,
    *,
    time_scale: float = 1.0,
    uart_timing: bool = False,
    link: str | os.PathLike[str] | None = None,
    clock: Clock | None = None,
) -> PtyServer:
    """Serve ``simulator`` on a new pseudo-terminal and return the running server.

    Open :attr:`PtyServer.path` as a serial port to talk to the simulated board; close
    the server (or leave its ``with`` block) to stop::

        with serve_on_pty(simulator) as server:
            print(server.path)

    :param simulator: the simulated board to serve.
    :param time_scale: multiplies the simulator's boot delay; ``0`` makes it (almost)
        instant.
    :param uart_timing: delay each reply by the time the board's UART would need to
        receive the request and send the reply.
    :param link: keep a symbolic link at this path pointing at the pseudo-terminal, also
        across an unplug (see the module's notes); removed when the server closes.
    :param clock: the clock the board's firmware timers follow; by default real time
        divided by ``time_scale`` (see :class:`PtyServer`).
    :raises ValueError: ``time_scale`` is negative.
    :raises FileExistsError: ``link`` exists and is not a symbolic link.
    :raises OSError: no pseudo-terminal could be made.
    """
    server = PtyServer(
        simulator, time_scale=time_scale, uart_timing=uart_timing, link=link, clock=clock
    )
    server.start()
    return server

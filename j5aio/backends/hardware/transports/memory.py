"""In-memory byte streams: a back-to-back pair, and a stream to a board simulator.

:func:`memory_stream_pair` connects two :class:`~.stream.ByteStream` ends: what one sends,
the other receives. :class:`SimulatorStream` connects the host to a board simulator (any
object shaped like :class:`SerialSimulatorLike`), which is how the simulated environment
runs the real hardware backends and protocol codecs without hardware.
"""

from __future__ import annotations

import asyncio
import time
from collections import deque
from typing import Protocol, runtime_checkable

import anyio
import anyio.lowlevel

from j5aio.errors import BoardDisconnectionError

from ._inbox import Inbox
from .stream import ByteStream

__all__ = ["MemoryStream", "SerialSimulatorLike", "SimulatorStream", "memory_stream_pair"]


class MemoryStream(ByteStream):
    """One end of an in-memory pair made by :func:`memory_stream_pair`."""

    def __init__(self, name: str) -> None:
        self._name = name
        self._inbox = Inbox()
        self._peer: MemoryStream | None = None
        self._closed = False

    @property
    def name(self) -> str:
        """The name given to this end."""
        return self._name

    @property
    def is_closed(self) -> bool:
        """Whether this end has been closed."""
        return self._closed

    async def send(self, data: bytes) -> None:
        """Deliver ``data`` to the other end.

        :raises BoardDisconnectionError: either end has been closed.
        """
        await anyio.lowlevel.checkpoint()
        MemoryStream.send_nowait(self, data)

    def send_nowait(self, data: bytes) -> bool:
        """Deliver ``data`` to the other end at once; see :meth:`.ByteStream.send_nowait`.

        Always sent (``True``).

        :raises BoardDisconnectionError: either end has been closed.
        """
        if self._closed:
            raise BoardDisconnectionError(f"{self._name}: the stream is closed")
        peer = self._peer
        if peer is None or peer._closed:
            raise BoardDisconnectionError(f"{self._name}: the other end has gone away")
        peer._inbox.feed(data)
        return True

    def send_now(self, data: bytes, timeout: float) -> None:
        """Deliver ``data`` to the other end at once; see :meth:`.ByteStream.send_now`."""
        if self._closed:
            raise BoardDisconnectionError(f"{self._name}: the stream is closed")
        peer = self._peer
        if peer is None or peer._closed:
            raise BoardDisconnectionError(f"{self._name}: the other end has gone away")
        peer._inbox.feed(bytes(data))

    async def receive(self, max_bytes: int = 4096) -> bytes:
        """Return bytes sent by the other end; see :meth:`.ByteStream.receive`."""
        return await self._inbox.take(max_bytes)

    async def receive_by(self, deadline: float, max_bytes: int = 4096) -> bytes | None:
        """Return received bytes, or ``None`` at ``deadline``.

        See :meth:`.ByteStream.receive_by`.
        """
        return await self._inbox.take_by(max_bytes, deadline)

    def close_now(self) -> None:
        """Close this end; the other end then receives what was already sent, then EOF."""
        if self._closed:
            return
        self._closed = True
        self._inbox.finish(
            BoardDisconnectionError(f"{self._name}: the stream is closed"), discard=True
        )
        if self._peer is not None:
            self._peer._inbox.finish(
                BoardDisconnectionError(f"{self._peer._name}: the other end has gone away")
            )


def memory_stream_pair(
    name_a: str = "memory-a", name_b: str = "memory-b"
) -> tuple[MemoryStream, MemoryStream]:
    """Return two streams connected back to back: bytes sent to one are received by the other.

    Closing one end lets the other read what was already sent and then get
    :class:`~j5aio.errors.BoardDisconnectionError`.
    """
    a, b = MemoryStream(name_a), MemoryStream(name_b)
    a._peer, b._peer = b, a
    return a, b


@runtime_checkable
class SerialSimulatorLike(Protocol):
    """The shape of a board simulator that speaks a serial protocol.

    The simulators in :mod:`j5aio.simulator` have this shape; so may a team's own.
    """

    @property
    def baudrate(self) -> int:
        """The baud rate the simulated board's UART runs at."""
        ...

    @property
    def boot_delay(self) -> float:
        """Seconds between opening the port and the boot output appearing."""
        ...

    @property
    def connected(self) -> bool:
        """Whether the simulated board is still plugged in."""
        ...

    def open(self) -> bytes:
        """Handle the host opening the port; return the boot output (may be empty)."""
        ...

    def receive(self, data: bytes) -> bytes:
        """Handle bytes written by the host; return the board's response (may be empty)."""
        ...


class SimulatorStream(ByteStream):
    """A byte stream whose far end is a board simulator.

    The simulator's :meth:`~SerialSimulatorLike.open` is called when the stream is
    made; its boot output appears after ``boot_delay * time_scale`` seconds. Every
    :meth:`send` goes to the simulator's :meth:`~SerialSimulatorLike.receive` at once,
    and its response is queued to be received, in order, never ahead of earlier output.

    :param simulator: the simulated board.
    :param name: the name used in errors and logs; defaults to the simulator's class name.
    :param time_scale: multiplies every simulated delay; ``0`` makes them all instant.
    :param uart_timing: if true, delay each transfer by the time a UART at the
        simulator's baud rate takes (10 bit times a byte), request and response both.
    :param poll_interval: how often a waiting :meth:`receive` checks that the board is
        still connected, in seconds.
    """

    def __init__(
        self,
        simulator: SerialSimulatorLike,
        *,
        name: str | None = None,
        time_scale: float = 1.0,
        uart_timing: bool = False,
        poll_interval: float = 0.02,
    ) -> None:
        if time_scale < 0:
            raise ValueError(f"time_scale must not be negative, not {time_scale}")
        self._simulator = simulator
        self._name = name if name is not None else f"simulated {type(simulator).__name__}"
        self._time_scale = time_scale
        self._uart_timing = uart_timing
        self._poll_interval = poll_interval
        self._closed = False
        # Output not yet received: (monotonic time it becomes visible, bytes), in order.
        self._pending: deque[tuple[float, bytes]] = deque()
        self._last_due = time.monotonic()
        self._wakeup: anyio.Event | None = None
        self._connection = getattr(simulator, "connection", None)
        self._queue_output(simulator.open(), after=simulator.boot_delay * time_scale)

    @property
    def name(self) -> str:
        """The name of the simulated board, as used in errors and logs."""
        return self._name

    @property
    def is_closed(self) -> bool:
        """Whether this stream has been closed."""
        return self._closed

    @property
    def simulator(self) -> SerialSimulatorLike:
        """The simulated board at the far end."""
        return self._simulator

    async def send(self, data: bytes) -> None:
        """Hand ``data`` to the simulator and queue its response.

        As on a real port, a cancelled caller sends nothing, and otherwise the bytes go
        at once, with no turn of the event loop first (the caller yields while it waits
        for the reply).

        :raises BoardDisconnectionError: the simulated board is disconnected, or the
            stream is closed.
        """
        await anyio.lowlevel.checkpoint_if_cancelled()
        # This class's own (a subclass with a send of its own has the default back).
        SimulatorStream.send_nowait(self, data)

    def send_nowait(self, data: bytes) -> bool:
        """Hand ``data`` to the simulator at once; see :meth:`.ByteStream.send_nowait`.

        Always sent (``True``): the simulator takes every byte at once.

        :raises BoardDisconnectionError: the simulated board is disconnected, or the
            stream is closed.
        """
        simulator = self._simulator
        if (
            self._closed
            or not simulator.connected
            or getattr(simulator, "connection", None) != self._connection
        ):
            self._check_usable()  # raises, saying why
        response = simulator.receive(data)
        self._queue_output(response, after=self._wire_time(data))
        return True

    def send_now(self, data: bytes, timeout: float) -> None:
        """Hand ``data`` to the simulator at once; see :meth:`.ByteStream.send_now`."""
        self._check_usable()
        response = self._simulator.receive(bytes(data))
        self._queue_output(response, after=self._wire_time(data))

    async def receive(self, max_bytes: int = 4096) -> bytes:
        """Return the simulator's output once it is due; see :meth:`.ByteStream.receive`."""
        if max_bytes < 1:
            raise ValueError(f"max_bytes must be at least 1, not {max_bytes}")
        await anyio.lowlevel.checkpoint()
        return await self._receive_after_checkpoint(max_bytes)

    async def receive_by(self, deadline: float, max_bytes: int = 4096) -> bytes | None:
        """As :meth:`receive`, but ``None`` if nothing has come by ``deadline``.

        See :meth:`.ByteStream.receive_by`. A reply already due when the caller's turn
        comes back (the usual case: a simulator answers at once) is returned with no
        cancel scope; a wait for one runs in a scope with that deadline, as the default's.
        """
        if max_bytes < 1:
            raise ValueError(f"max_bytes must be at least 1, not {max_bytes}")
        await anyio.lowlevel.checkpoint()
        if asyncio.get_running_loop().time() >= deadline:
            return None  # (as the default's scope, whose deadline has passed, would say)
        due = self._take_if_due(max_bytes)
        if due is not None:
            return due
        with anyio.CancelScope(deadline=deadline):
            return await self._receive_after_checkpoint(max_bytes)
        return None

    def _take_if_due(self, max_bytes: int) -> bytes | None:
        """Up to ``max_bytes`` of the output due now, or ``None`` if none is.

        :raises BoardDisconnectionError: the simulated board is disconnected, or the
            stream is closed.
        """
        simulator = self._simulator
        if (
            self._closed
            or not simulator.connected
            or getattr(simulator, "connection", None) != self._connection
        ):
            self._check_usable()  # raises, saying why
        pending = self._pending
        if pending:
            now = time.monotonic()
            if pending[0][0] <= now:
                if len(pending) == 1 and len(pending[0][1]) <= max_bytes:
                    return bytes(pending.popleft()[1])  # one reply, whole (the usual case)
                return self._take_due(now, max_bytes)
        return None

    async def _receive_after_checkpoint(self, max_bytes: int) -> bytes:
        """:meth:`receive` once its checkpoint is passed: wait until output is due."""
        while True:
            due = self._take_if_due(max_bytes)
            if due is not None:
                return due
            wait = self._poll_interval
            if self._pending:
                wait = min(wait, self._pending[0][0] - time.monotonic())
            self._wakeup = anyio.Event()
            with anyio.move_on_after(wait):
                await self._wakeup.wait()

    def close_now(self) -> None:
        """Close the stream; a waiting :meth:`receive` is woken and raises."""
        self._closed = True
        self._pending.clear()
        if self._wakeup is not None:
            self._wakeup.set()

    def _check_usable(self) -> None:
        if self._closed:
            raise BoardDisconnectionError(f"{self._name}: the stream is closed")
        if (
            not self._simulator.connected
            or getattr(self._simulator, "connection", None) != self._connection
        ):
            # Unplugged, or unplugged and back since this port was opened: like a real
            # port, this one is dead for good; the board must be opened again.
            self._pending.clear()
            raise BoardDisconnectionError(
                f"{self._name}: the simulated board has been disconnected"
            )

    def _wire_time(self, data: bytes) -> float:
        if not self._uart_timing or not data:
            return 0.0
        return len(data) * 10 / self._simulator.baudrate * self._time_scale

    def _queue_output(self, data: bytes, *, after: float) -> None:
        # Output never overtakes earlier output, as on a real wire.
        due = max(self._last_due, time.monotonic() + after) + self._wire_time(data)
        self._last_due = due
        if data:
            self._pending.append((due, data))
            if self._wakeup is not None:
                self._wakeup.set()

    def _take_due(self, now: float, max_bytes: int) -> bytes:
        taken = bytearray()
        while self._pending and self._pending[0][0] <= now and len(taken) < max_bytes:
            due, chunk = self._pending.popleft()
            room = max_bytes - len(taken)
            taken += chunk[:room]
            if len(chunk) > room:
                self._pending.appendleft((due, chunk[room:]))
        return bytes(taken)

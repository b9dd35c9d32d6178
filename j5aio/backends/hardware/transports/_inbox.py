"""A receive buffer fed by callbacks and drained by one awaiting reader (internal).

Streams whose bytes arrive through callbacks (asyncio protocols, an in-memory peer) put
them here; :meth:`Inbox.take` waits for them. Feeding is synchronous and needs no async
context, so asyncio protocol callbacks may call :meth:`Inbox.feed` and
:meth:`Inbox.finish`. Waiting is cancel-safe: bytes are only removed from the buffer when
they are returned.
"""

from __future__ import annotations

import asyncio
import copy
import math

import anyio.lowlevel

from j5aio.errors import CommunicationError

__all__ = ["Inbox", "fresh_copy"]


def fresh_copy(error: CommunicationError) -> CommunicationError:
    """Return a copy of ``error`` with its cause, to raise again without piling up tracebacks."""
    again = copy.copy(error)
    again.__cause__ = error.__cause__
    return again


class Inbox:
    """Bytes received but not yet read, plus the reason the stream ended, if it has."""

    def __init__(self) -> None:
        self._buffer = bytearray()
        self._error: CommunicationError | None = None
        # The reader's wake-up: a bare future of the running loop, the cheapest thing
        # to wait on (an anyio cancellation reaches it as it reaches any await).
        self._wakeup: asyncio.Future[object] | None = None
        # take_by's timer, kept from one wait to the next (see take_by): when it fires,
        # on which loop, and the deadline of the wait in progress (infinite for take).
        self._timer: asyncio.TimerHandle | None = None
        self._timer_at = math.inf
        self._timer_loop: asyncio.AbstractEventLoop | None = None
        self._deadline = math.inf

    @property
    def ended(self) -> bool:
        """Whether :meth:`finish` has been called."""
        return self._error is not None

    def __len__(self) -> int:
        return len(self._buffer)

    def feed(self, data: bytes) -> None:
        """Append received bytes and wake the reader; ignored once ended."""
        if self._error is None and data:
            self._buffer += data
            # (What _wake does, written out: on the path of every reply.)
            waiter = self._wakeup
            if waiter is not None and not waiter.done():
                waiter.set_result(None)

    def finish(self, error: CommunicationError, *, discard: bool = False) -> None:
        """End the stream: once the buffer is empty, :meth:`take` raises ``error``.

        With ``discard`` the bytes still buffered are dropped, so ``error`` is raised at
        once. Only the first call has an effect.
        """
        if self._error is None:
            self._error = error
            if discard:
                self._buffer.clear()
            self._wake()

    async def take(self, max_bytes: int) -> bytes:
        """Return 1 to ``max_bytes`` buffered bytes, waiting for some to arrive."""
        if max_bytes < 1:
            raise ValueError(f"max_bytes must be at least 1, not {max_bytes}")
        if self._buffer:
            await anyio.lowlevel.checkpoint()
        while not self._buffer:  # waiting yields to the event loop: no checkpoint first
            if self._error is not None:
                await anyio.lowlevel.checkpoint()
                raise fresh_copy(self._error)
            self._wakeup = asyncio.get_running_loop().create_future()
            self._deadline = math.inf
            try:
                await self._wakeup
            finally:
                self._wakeup = None
        data = bytes(self._buffer[:max_bytes])
        del self._buffer[:max_bytes]
        return data

    async def take_by(self, max_bytes: int, deadline: float) -> bytes | None:
        """As :meth:`take`, but ``None`` if nothing has arrived by ``deadline``.

        ``deadline`` is on the event loop's clock. Waiting needs no cancel scope, and
        mostly no new timer: one request after another waits by much the same deadline
        (a second or so from now, where the reply comes in milliseconds), so the timer
        is kept from one wait to the next. A timer due by the deadline is kept; when it
        fires before the deadline of the wait then in progress, it is set again for that
        deadline (once a timeout or so); one due after the deadline is set earlier.
        """
        if max_bytes < 1:
            raise ValueError(f"max_bytes must be at least 1, not {max_bytes}")
        if self._buffer:
            await anyio.lowlevel.checkpoint()
        while not self._buffer:
            if self._error is not None:
                raise fresh_copy(self._error)
            loop = asyncio.get_running_loop()
            waiter = self._wakeup = loop.create_future()
            self._deadline = deadline
            if self._timer is None or self._timer_at > deadline or self._timer_loop is not loop:
                self._set_timer(loop, deadline)
            try:
                await waiter
            finally:
                self._wakeup = None
            if not self._buffer and waiter.result() is _EXPIRED:
                return None
        data = bytes(self._buffer[:max_bytes])
        del self._buffer[:max_bytes]
        return data

    def _set_timer(self, loop: asyncio.AbstractEventLoop, when: float) -> None:
        if self._timer is not None:
            self._timer.cancel()
        self._timer = loop.call_at(when, self._on_timer)
        self._timer_at = when
        self._timer_loop = loop

    def _on_timer(self) -> None:
        """The timer has fired: end the wait in progress if its deadline has come."""
        self._timer = None
        waiter, deadline = self._wakeup, self._deadline
        if waiter is None or waiter.done() or deadline == math.inf:
            return  # no wait by a deadline: the timer lapses until the next one sets it
        if self._timer_at >= deadline:
            waiter.set_result(_EXPIRED)
        else:  # set for an earlier wait's deadline: this wait's is later
            self._set_timer(waiter.get_loop(), deadline)

    def _wake(self) -> None:
        if self._wakeup is not None and not self._wakeup.done():
            self._wakeup.set_result(None)


#: What a waiter's timer sets it to (a wake-up by bytes or an end sets ``None``).
_EXPIRED = object()

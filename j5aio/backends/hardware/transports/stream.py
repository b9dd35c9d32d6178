"""The byte-stream seam: the one interface every transport above it depends on.

A :class:`ByteStream` moves bytes to and from one board. Serial ports
(:mod:`.serial_stream`), in-memory pairs and board simulators (:mod:`.memory`) and the
fault-injecting fakes in :mod:`j5aio.testing.transports` all implement it, so that
:class:`~.serial_link.SerialLink` and every backend above it never know which library, if
any, carries the bytes. Replacing pyserial with another serial library means writing one
new ``ByteStream``.

The contract that implementations keep:

* :meth:`ByteStream.receive` returns at least one byte. It raises
  :class:`~j5aio.errors.BoardDisconnectionError` once the far end has gone (after any
  bytes that arrived before that were returned) and once the stream has been closed.
* Failures are reported as :class:`~j5aio.errors.CommunicationError` (or a subclass),
  never as the exception of an underlying library.
* :meth:`ByteStream.receive` is cancel-safe: when it is cancelled, no byte is lost; bytes
  not yet returned stay for the next call.
* :meth:`ByteStream.close_now` closes synchronously, without an executor or a running
  event loop, so that it works inside ``atexit`` handlers. Call it from the thread that
  runs the event loop, or after that loop has stopped.
"""

from __future__ import annotations

import abc

import anyio.lowlevel
from anyio.abc import AsyncResource

from j5aio.errors import CommunicationError

__all__ = ["ByteStream"]


class ByteStream(AsyncResource):
    """A bidirectional stream of bytes to one board.

    Use it as an async context manager, or close it with :meth:`aclose` or
    :meth:`close_now`.
    """

    def __init_subclass__(cls, **kwargs: object) -> None:
        super().__init_subclass__(**kwargs)
        # A class with a send (or receive) of its own (a wrapper, a test's fault) must
        # see every request (and reply) go through it: a send_nowait (or receive_by) it
        # inherits would go round it, so it gets the defaults, which use its own.
        if "send" in cls.__dict__ and "send_nowait" not in cls.__dict__:
            cls.send_nowait = ByteStream.send_nowait  # type: ignore[method-assign]
        if "receive" in cls.__dict__ and "receive_by" not in cls.__dict__:
            cls.receive_by = ByteStream.receive_by  # type: ignore[method-assign]

    @property
    @abc.abstractmethod
    def name(self) -> str:
        """A human name for the far end, such as the port path; used in errors and logs."""

    @property
    @abc.abstractmethod
    def is_closed(self) -> bool:
        """Whether this stream has been closed from this side."""

    @abc.abstractmethod
    async def send(self, data: bytes) -> None:
        """Send ``data`` to the far end.

        :raises BoardDisconnectionError: the far end has gone or the stream is closed.
        :raises CommunicationError: the bytes could not be sent.
        """

    def send_nowait(self, data: bytes) -> bool:
        """Send ``data`` at once if that needs no wait, and say whether it was sent.

        For a caller that has already checked for cancellation and runs shielded from
        it (:class:`~.serial_link.SerialLink`, once it holds its lock): it skips the
        check :meth:`send` makes, and the coroutine. ``False`` means nothing was sent;
        :meth:`send` then waits until it can. The default always says ``False``: a
        stream that can send without waiting overrides it. A subclass that overrides
        :meth:`send` alone gets this default back, so that its :meth:`send` sees every
        request.

        :raises BoardDisconnectionError: the far end has gone or the stream is closed.
        :raises CommunicationError: the bytes could not be sent.
        """
        return False

    @abc.abstractmethod
    async def receive(self, max_bytes: int = 4096) -> bytes:
        """Return between 1 and ``max_bytes`` bytes, waiting until at least one arrives.

        :raises BoardDisconnectionError: the far end has gone (end of stream) or the
            stream is closed.
        :raises CommunicationError: reading failed.
        """

    async def receive_by(self, deadline: float, max_bytes: int = 4096) -> bytes | None:
        """As :meth:`receive`, but return ``None`` if nothing has arrived by ``deadline``.

        ``deadline`` is on the event loop's clock (``anyio.current_time()``). The
        default runs :meth:`receive` in a cancel scope with that deadline; a stream
        that can wait more cheaply overrides it. A subclass that overrides
        :meth:`receive` alone gets this default back.
        """
        with anyio.CancelScope(deadline=deadline):
            return await self.receive(max_bytes)
        return None

    @abc.abstractmethod
    def close_now(self) -> None:
        """Close the stream at once, synchronously; idempotent.

        A task waiting in :meth:`receive` is woken and gets
        :class:`~j5aio.errors.BoardDisconnectionError`.
        """

    def send_now(self, data: bytes, timeout: float) -> None:
        """Send ``data`` at once, synchronously, within ``timeout`` seconds.

        For the last word a program has with its board (the safe state at exit, from the
        safety net in :mod:`j5aio.lifetime`): no event loop needs to be running. Output
        still queued by :meth:`send` may be dropped, so send a protocol's resynchronising
        bytes first if a half-sent command could swallow ``data``. Call it from the thread
        that runs the event loop, or after that loop has stopped.

        The default refuses: a stream that can do this overrides it.

        :raises BoardDisconnectionError: the far end has gone or the stream is closed.
        :raises CommunicationError: the bytes could not be sent in time, or this stream
            cannot send synchronously.
        """
        raise CommunicationError(f"{self.name}: this stream cannot send synchronously")

    async def aclose(self) -> None:
        """Close the stream; idempotent.

        The default closes at once with :meth:`close_now`; implementations with an output
        buffer may first let it drain for a bounded time.
        """
        self.close_now()
        await anyio.lowlevel.checkpoint()

    def __repr__(self) -> str:
        state = "closed" if self.is_closed else "open"
        return f"<{type(self).__name__} {self.name!r} {state}>"

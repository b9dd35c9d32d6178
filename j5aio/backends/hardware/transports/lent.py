"""A byte stream lent out: closing it ends the loan, and leaves the stream open.

Identification (:mod:`j5aio.backends.hardware.identify`) lends one open port to several
kinds' handshakes in turn, so that each need not open the port afresh.
"""

from __future__ import annotations

import anyio
import anyio.lowlevel

from j5aio.errors import BoardDisconnectionError

from .stream import ByteStream

__all__ = ["LentStream"]


class LentStream(ByteStream):
    """``stream``, until this loan is closed; then it refuses, and ``stream`` stays open.

    A task waiting in :meth:`receive` when the loan is closed gets
    :class:`~j5aio.errors.BoardDisconnectionError`, as on a closed stream.

    :param stream: the stream lent; its owner closes it.
    """

    def __init__(self, stream: ByteStream) -> None:
        self._stream = stream
        self._ended = anyio.Event()

    @property
    def name(self) -> str:
        """The lent stream's name."""
        return self._stream.name

    @property
    def is_closed(self) -> bool:
        """Whether the loan has ended (or the stream itself is closed)."""
        return self._ended.is_set() or self._stream.is_closed

    def _check_open(self) -> None:
        if self.is_closed:
            raise BoardDisconnectionError(f"{self.name}: the stream is no longer lent")

    async def send(self, data: bytes) -> None:
        """Send ``data`` on the lent stream."""
        self._check_open()
        await self._stream.send(data)

    async def receive(self, max_bytes: int = 4096) -> bytes:
        """Receive from the lent stream, until the loan ends."""
        self._check_open()
        received: bytes | None = None
        async with anyio.create_task_group() as group:

            async def end_with_the_loan() -> None:
                await self._ended.wait()
                group.cancel_scope.cancel()

            group.start_soon(end_with_the_loan)
            received = await self._stream.receive(max_bytes)
            group.cancel_scope.cancel()
        if received is None:
            raise BoardDisconnectionError(f"{self.name}: the stream is no longer lent")
        return received

    def close_now(self) -> None:
        """End the loan (the stream stays open)."""
        self._ended.set()

    async def aclose(self) -> None:
        """End the loan (the stream stays open)."""
        self.close_now()
        await anyio.lowlevel.checkpoint()

"""The shared base of the backends of the SR v4 boards' 2023 text firmwares.

Each command is one line and gets one reply line (see :mod:`.text_protocol`). This base
sends a command and reads its reply, turning a NACK or a reply the firmware cannot send
into a :class:`~j5aio.errors.CommunicationError` that names the board and the command.

Late replies: these firmwares answer in order, and nothing in a reply names its request,
so after a request timed out (its reply may still come) the link resynchronises before
the next request: it sends ``ECHO:<nonce>``, which the firmware answers with the nonce
alone, and discards every line up to that answer. The nonce is new each time, so not
even a late answer to an earlier probe is mistaken for it.
"""

from __future__ import annotations

from collections.abc import Awaitable, Callable
from typing import TypeVar

from j5aio.backends.hardware.serial_backend import SerialHardwareBackend
from j5aio.backends.hardware.sr.v4.text_protocol import (
    ACK,
    NACK_PREFIX,
    check_ack,
    check_not_nack,
    echo_probe,
)
from j5aio.backends.hardware.transports.readers import read_line
from j5aio.errors import BoardDisconnectionError, CommunicationTimeoutError

__all__ = ["SRTextBackend"]

T = TypeVar("T")

#: The longest reply line of these firmwares (their reply buffers are 64 bytes).
_REPLY = read_line(max_length=128)


class SRTextBackend(SerialHardwareBackend):
    """Sends the one-line commands of an SR 2023 text firmware and checks the replies."""

    def _link_ready(self) -> None:
        self._link.set_resync_line(echo_probe)

    def _explain_timeout(self, error: CommunicationTimeoutError) -> CommunicationTimeoutError:
        """Return the timeout a caller sees: ``error`` here; a board may add a hint."""
        return error

    async def _query(self, command: bytes) -> bytes:
        """Send ``command`` and return its reply line (a NACK raises :class:`NackError`)."""
        try:
            try:  # the steps of the backend's guarded exchange, written out (see _act)
                if self._lost or self._closed_for_good:
                    await self._check_connected()
                reply = await self._link.exchange(command, _REPLY)
            except BoardDisconnectionError as lost:

                def again() -> Awaitable[bytes]:  # the link is looked up anew
                    return self._link.exchange(command, _REPLY)

                reply = await self._retry_after(lost, again, idempotent=True)
        except CommunicationTimeoutError as error:
            explained = self._explain_timeout(error)
            if explained is error:
                raise
            raise explained from error
        if reply.startswith(NACK_PREFIX):
            check_not_nack(self.board.name, command, reply)  # raises, with the reason
        return reply

    async def _query_then(self, command: bytes, then: Callable[[bytes], T]) -> T:
        """Send ``command`` and return ``then(reply line)``, as :meth:`_query` checks it.

        ``then`` runs as soon as the reply has arrived, even for a cancelled caller: where
        a reply that must not be lost (a latched button press) is taken.
        """

        def checked(reply: bytes) -> T:
            if reply.startswith(NACK_PREFIX):
                check_not_nack(self.board.name, command, reply)  # raises, with the reason
            return then(reply)

        try:
            try:  # the steps of the backend's guarded exchange, written out (see _act)
                if self._lost or self._closed_for_good:
                    await self._check_connected()
                return await self._link.exchange(command, _REPLY, then=checked)
            except BoardDisconnectionError as lost:

                def again() -> Awaitable[T]:  # the link is looked up anew
                    return self._link.exchange(command, _REPLY, then=checked)

                return await self._retry_after(lost, again, idempotent=True)
        except CommunicationTimeoutError as error:
            explained = self._explain_timeout(error)
            if explained is error:
                raise
            raise explained from error

    async def _act(
        self,
        command: bytes,
        *,
        then: Callable[[], None] | None = None,
        idempotent: bool = True,
    ) -> None:
        """Send an action ``command`` and check that the board acknowledges it.

        Inside :func:`~j5aio.backends.acknowledgements.acknowledge_later` it returns once
        the command is written; the acknowledgement is checked before the next request.

        :param then: runs once the board has acknowledged ``command`` (even for a
            cancelled caller): where a backend updates what it remembers of the board.
        :param idempotent: ``False`` for a command that must not be sent again after
            the board vanished and came back (see :mod:`j5aio.backends.hardware.reconnect`).
        """

        def acknowledged(reply: bytes) -> None:
            if reply != ACK:
                check_ack(self.board.name, command, reply)  # raises, saying what came
            if then is not None:
                then()

        try:
            # What the backend's command() does, written out: one call fewer on every
            # motor, servo and power output command. A lost board is looked for first;
            # one that vanishes under the call is handed to the reconnection policy.
            try:
                if self._lost or self._closed_for_good:
                    await self._check_connected()
                await self._link.command(command, _REPLY, then=acknowledged)
            except BoardDisconnectionError as lost:

                def again() -> Awaitable[None]:  # the link is looked up anew
                    return self._link.command(command, _REPLY, then=acknowledged)

                await self._retry_after(lost, again, idempotent=idempotent)
        except CommunicationTimeoutError as error:
            explained = self._explain_timeout(error)
            if explained is error:
                raise
            raise explained from error

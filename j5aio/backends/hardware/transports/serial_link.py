"""One :class:`SerialLink` per open port: serialised requests, replies never mixed up.

Design
======

**Who reads.** The link has no reader task. It keeps a buffer of received bytes and pulls
from its :class:`~.stream.ByteStream` only while a caller holds the link's lock and waits
for a reply (an :meth:`~SerialLink.exchange`, a :meth:`~SerialLink.read_line`, a
:meth:`~SerialLink.drain`). This is enough because every stream buffers what arrives on
its own side (the asyncio protocol, the in-memory inbox), so nothing is lost between
requests, and the protocols driven through it (SR, SB, Ruggeduino) only ever speak in
reply to the host, apart from a boot banner which is read on purpose. Without a task the
link needs no task group, no start-up and no owner: it can be made anywhere, used from
any task, and closed synchronously with :meth:`~SerialLink.close_now` (in ``atexit``,
say); :meth:`~SerialLink.send_now` likewise sends a board's safe state synchronously.
A reader task would only add a second place where bytes wait.

**Serialisation.** One :class:`anyio.Lock` (FIFO) per link: sends, exchanges, plain reads
and drains run one at a time, in the order they asked.

**Cancellation.** The trap: a request cancelled after its bytes were written leaves its
reply on the line, and the next request reads it. So an exchange (write the request,
read the reply) is never torn: a caller that is cancelled part way still has its
exchange complete and consume its own reply, and the cancellation takes effect once the
exchange is over (at worst ``timeout`` later; plus the bounded drain described next).
Cancelling a caller that is still waiting for the lock is immediate and sends nothing.
On a link in step whose stream takes the bytes at once
(:meth:`~.stream.ByteStream.send_nowait`: the common case, every request of a working
robot) the only thing awaited after the write is the reply, by the stream's own timer
(:meth:`~.stream.ByteStream.receive_by`); a cancellation that reaches that wait,
anyio's or asyncio's, is handled as the next paragraph says, with no cancel scope on
the way (a scope costs more than the rest of the request's path to its bytes). Every
other exchange (one that first cleans the line, or whose stream makes it wait to
write) runs inside ``anyio.CancelScope(shield=True)``, with the timeout *inside* the
shield.

**Timeouts and the dirty flag.** A timeout is the only way an exchange can end while its
reply may still be coming. After a timeout (or any exchange that did not finish: a stream
error, an unparseable reply, an asyncio ``Task.cancel`` that broke through the shield)
the link is marked *dirty*. The next exchange first discards input until the line has
been quiet for ``quiet_time`` (default 20 ms), for at most ``drain_limit`` (then it raises
:class:`~j5aio.errors.CommunicationError` and stays dirty). Bytes left in the link's
buffer when an exchange starts (the rest of a boot banner, extra bytes after a reply)
are never a reply to the new request: they are discarded, and extra bytes after a reply
mark the link dirty.

**Native asyncio cancellation.** ``asyncio.Task.cancel()`` (used by ``asyncio.timeout``
and ``asyncio.wait_for``) breaks through anyio shields. So, once the lock is held, the
exchange runs to completion (:func:`~.completion.run_to_completion`) in a task that no
caller's cancellation reaches; the caller waits for it either way and is cancelled
afterwards. That task is made only when needed (a task for every call would cost tens
of microseconds): an exchange or a send runs in the caller's task, and if ``Task.cancel``
(or, on the unshielded path above, anyio) tears it after its request has gone, a task
of its own reads the reply to its end, by the same deadline, while the caller waits.
(A stream sends all of a request or, cancelled, none of it, so a request torn before it
went needs no reply, and a send has nothing left to do once its bytes have gone.) An
exchange is therefore never torn half way, whoever cancels. A ``then`` callback given to
:meth:`~SerialLink.exchange` or :meth:`~SerialLink.send` runs as soon as the board has
answered (or the bytes have gone), even for a cancelled caller: that is where a backend
updates what it remembers of the board, so its caches change when, and only when, the
board has been told.

**Correlation: which reply belongs to which request.** After a timeout the reply may
still be on its way, and the next request must not take it. Each protocol gets the
strongest rule its firmware allows:

1. *Correlated replies.* A reader whose :attr:`~.readers.ReplyReader.correlates` is
   true (see :func:`~.readers.matching`) recognises replies to other requests and skips
   them, however late they come. A dirty link then needs no draining at all (the SB
   Arduino 2019 firmware: request ids and command echoes). Tagging costs bytes on the
   wire, and only a link that has had a timeout can have a reply outstanding, so a
   backend may send the plain request on a clean link and the tagged one otherwise
   (``when_dirty`` of :meth:`~SerialLink.exchange`): requests are tagged while the link
   is dirty or a reply to a request that timed out has not been skipped yet (for at
   most ``late_limit`` seconds), so that even a late reply that comes after later ones
   is skipped.
2. *A resynchronisation probe.* Where nothing in a reply names its request, a backend
   can name a harmless probe whose answer is known (:meth:`~SerialLink.set_resync`).
   The first exchange or send on a dirty link sends the probe and discards every byte up
   to and including the known answer. The board answers in order, so everything owed
   to earlier requests came before it (the Ruggeduino's ``v``, the motor board's
   ``00 01``).

   For a line protocol (:meth:`~SerialLink.set_resync_line`: one reply line per
   request, and a probe answered by one known line, fresh each time where the firmware
   can echo a nonce) the link does more, so that a late reply is never taken even if
   it comes *after* replies to later requests. It counts the reply lines owed by
   requests that timed out; while any is owed (for at most ``late_limit`` seconds
   after the last timeout), every exchange is sent between two probes, ``probe,
   request, probe``: lines before the first probe's answer are owed lines, discarded
   and counted off, and the reply is the one thing between the two answers. A late
   line that lands between them leaves two things there: the exchange then raises
   :class:`~j5aio.errors.CommunicationError` rather than guess. Once every owed line
   has come, requests go plain again.
3. *Otherwise,* input is discarded until the line has been quiet for ``quiet_time``.
   This is a guess about timing, and only as good as the guess.

**Acknowledgements confirmed later.** A command whose reply only acknowledges it goes
through :meth:`~SerialLink.command`. Inside
:func:`~j5aio.backends.acknowledgements.acknowledge_later`, on a link in step, it returns
once its bytes are written and the link remembers the one acknowledgement it is owed:
the link's next request (exchange, send, command, read, drain, :meth:`~SerialLink.confirm`)
first reads and checks it, by the command's own deadline and shielded like an exchange,
so that each board still has one request outstanding and the rules above hold
unchanged. A failure found then is logged and raised as
:class:`~j5aio.errors.EarlierCommandError` instead of sending the next request (except
while the boards are being made safe, whose safe state is sent regardless).
:meth:`~SerialLink.aclose` reads what is owed; :meth:`~SerialLink.close_now` and
:meth:`~SerialLink.send_now` cannot wait, so they log that it went unchecked (after
:meth:`~SerialLink.send_now` the link is dirty, and resynchronises past the reply).

**Errors.** A timeout raises :class:`~j5aio.errors.CommunicationTimeoutError` naming the
port and what was sent; a vanished port raises
:class:`~j5aio.errors.BoardDisconnectionError`; a reply a reader cannot parse raises
:class:`~j5aio.errors.UnexpectedReplyError`, and the bytes received so far are discarded
(they are noise, or out of step: keeping them would fail every later request, correlated
or not); a stray ``OSError`` or anyio stream error
from a stream is wrapped in :class:`~j5aio.errors.CommunicationError`.

**Wire log.** Every chunk sent and received is logged at
:data:`~.trace.TRACE` on ``j5aio.wire.<port>``.
"""

from __future__ import annotations

import asyncio
import logging
import math
import sys
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, Final, TypeGuard, TypeVar, overload

import anyio
import anyio.lowlevel
from anyio.abc import AsyncResource

from j5aio.backends.acknowledgements import LATER_SWITCH as _LATER_SWITCH
from j5aio.backends.safe_state_pass import making_safe
from j5aio.errors import (
    BoardDisconnectionError,
    CommunicationError,
    CommunicationTimeoutError,
    EarlierCommandError,
    UnexpectedReplyError,
)

from .completion import run_to_completion
from .readers import ReplyReader, read_line
from .stream import ByteStream
from .trace import TRACE, log_wire, wire_logger

if TYPE_CHECKING:
    from ._more_readers import LinesReader, MatchingReader

__all__ = ["SerialLink"]


class _Progress:
    """How far an exchange got: ``deadline`` is set once its request has gone.

    A bracketed exchange (see :meth:`SerialLink._bracketed_locked`) also notes the two
    answers it waits for, which it has seen, and how many lines it is still owed, so
    that a task that finishes it (after ``Task.cancel``) goes on where it stopped.
    """

    # Defaults on the class, and no ``__init__``: making one runs no Python code (it is
    # made on the path of every acknowledgement confirmed later).
    deadline: float | None = None
    seconds: float = 0.0
    bracket: tuple[bytes, bytes] | None = None
    opened: bool = False
    replied: bool = False
    reply: Any = None
    remaining: int = 0


class _OwedAcknowledgement:
    """A command written whose acknowledgement is still to be read (see ``command``)."""

    __slots__ = ("deadline", "reader", "request", "seconds", "then")

    def __init__(
        self,
        request: bytes,
        reader: ReplyReader[Any],
        then: Callable[[Any], object] | None,
        deadline: float,
        seconds: float,
    ) -> None:
        self.request = request
        self.reader = reader
        self.then = then
        self.deadline = deadline
        self.seconds = seconds


T = TypeVar("T")
U = TypeVar("U")

_log = logging.getLogger(__name__)

_DISCONNECTION_ERRORS = (anyio.EndOfStream, anyio.BrokenResourceError, anyio.ClosedResourceError)
#: What a stream's ``send`` may raise that the link turns into a CommunicationError.
_WRITE_ERRORS = (*_DISCONNECTION_ERRORS, OSError)


def _check_duration(name: str, value: float) -> float:
    if not value > 0 or math.isnan(value):
        raise ValueError(f"{name} must be a positive number of seconds, not {value!r}")
    return value


# The readers module defines its rarer readers in this module on their first use: until it
# is loaded, no reader can be one of them (and nothing is imported to find that out).
_MORE_READERS = f"{__package__}._more_readers"


def _is_lines_reader(reader: ReplyReader[Any]) -> TypeGuard[LinesReader]:
    more = sys.modules.get(_MORE_READERS)
    return more is not None and isinstance(reader, more.LinesReader)


class _NotYet:
    """What :meth:`SerialLink._take_reply` returns while a reply has not all arrived."""

    __slots__ = ()


_NOT_YET: Final = _NotYet()


def _is_matching_reader(reader: ReplyReader[T]) -> TypeGuard[MatchingReader[T]]:
    more = sys.modules.get(_MORE_READERS)
    return more is not None and isinstance(reader, more.MatchingReader)


def _lines_of(reader: ReplyReader[Any]) -> int:
    """How many lines a reply read by ``reader`` has, for counting late lines (1 if unsure)."""
    return reader.count if _is_lines_reader(reader) else 1


def _preview(data: bytes | bytearray, limit: int = 80) -> str:
    shown = repr(bytes(data[:limit]))
    return shown + (f" (+{len(data) - limit} more bytes)" if len(data) > limit else "")


class SerialLink(AsyncResource):
    """Requests and replies over one :class:`~.stream.ByteStream`, safely serialised.

    :param stream: the open stream to the board; the link owns it and closes it.
    :param name: the port name for errors and the wire log; defaults to the stream's.
    :param default_timeout: seconds to wait when a call gives no timeout.
    :param quiet_time: seconds of silence that count as "the line is quiet" when
        draining a dirty link.
    :param drain_limit: the longest a drain may take before giving up, in seconds.
    :param chunk_size: the most bytes asked of the stream at once.
    :param late_limit: with a line probe (:meth:`set_resync_line`), how long after a
        timeout a reply that never came is still waited for, in seconds (see the
        module's notes on late replies that overtake).
    """

    def __init__(
        self,
        stream: ByteStream,
        *,
        name: str | None = None,
        default_timeout: float = 1.0,
        quiet_time: float = 0.02,
        drain_limit: float = 0.5,
        chunk_size: int = 4096,
        late_limit: float = 2.0,
    ) -> None:
        self._stream = stream
        self._name = name if name is not None else stream.name
        self._default_timeout = _check_duration("default_timeout", default_timeout)
        self._quiet_time = _check_duration("quiet_time", quiet_time)
        self._drain_limit = _check_duration("drain_limit", drain_limit)
        self._late_limit = _check_duration("late_limit", late_limit)
        if chunk_size < 1:
            raise ValueError(f"chunk_size must be at least 1, not {chunk_size}")
        self._chunk_size = chunk_size
        # Uncontended, the lock is taken without yielding to the event loop: every
        # exchange waits for its reply anyway, and a yield before the request goes out
        # would only delay it (by a whole turn of the loop on a busy machine). asyncio's
        # lock is FIFO and is the cheapest there is; a caller already cancelled is
        # stopped before it by :meth:`_acquire`.
        self._lock = asyncio.Lock()
        self._buffer = bytearray()
        self._dirty = False
        self._closed = False
        self._wire = wire_logger(self._name)
        self._resync: tuple[bytes, bytes] | None = None
        self._resync_line: Callable[[], tuple[bytes, bytes]] | None = None
        self._resync_failed = False
        # Reply lines owed by requests that timed out, not yet seen (line protocols).
        self._owed = 0
        self._owed_until = 0.0
        # A command returned before its acknowledgement was read (see command()). Public
        # and a plain attribute, for a backend's every call tests it (as its
        # ``acknowledgement_owed``, without a call); only the link sets it.
        self.unconfirmed: _OwedAcknowledgement | None = None

    # -- state ---------------------------------------------------------------------------

    @property
    def name(self) -> str:
        """The port name used in errors and the wire log."""
        return self._name

    @property
    def stream(self) -> ByteStream:
        """The stream this link reads and writes."""
        return self._stream

    @property
    def is_closed(self) -> bool:
        """Whether the link has been closed."""
        return self._closed

    @property
    def is_dirty(self) -> bool:
        """Whether the next exchange will first drain input until the line is quiet."""
        return self._dirty

    @property
    def acknowledgement_owed(self) -> bytes | None:
        """The command whose acknowledgement is still to be read, if any (see :meth:`command`)."""
        return None if self.unconfirmed is None else self.unconfirmed.request

    @property
    def buffered(self) -> bytes:
        """Bytes received but not yet read (a copy, for inspection)."""
        return bytes(self._buffer)

    def mark_dirty(self) -> None:
        """Make the next exchange drain input first.

        Call it when a reply made no sense, so that whatever else the board sends is not
        taken as the reply to the next request.
        """
        self._dirty = True

    @property
    def resync_probe(self) -> tuple[bytes, bytes] | None:
        """The ``(probe, answer)`` used to resynchronise a dirty link, if one is set."""
        return self._resync

    def set_resync(self, probe: bytes, answer: bytes) -> None:
        """Resynchronise a dirty link by sending ``probe`` and waiting for ``answer``.

        For a protocol whose replies cannot be told apart: ``probe`` must change nothing
        on the board, and ``answer`` must be the exact bytes the board sends back (a
        version line, say). The first exchange or send on a dirty link then sends
        ``probe`` and discards input up to and including ``answer``, for at most
        ``drain_limit`` seconds, instead of waiting for a quiet line.

        :raises ValueError: an empty probe or answer.
        """
        if not probe or not answer:
            raise ValueError("a resynchronisation probe and its answer must not be empty")
        self._resync = (bytes(probe), bytes(answer))
        self._resync_line = None

    def set_resync_line(self, make: Callable[[], tuple[bytes, bytes]]) -> None:
        r"""Resynchronise a dirty link with a probe answered by one known line.

        For a line protocol whose replies cannot be told apart (one reply line per
        request, nothing in it naming the request). ``make`` is called before each
        resynchronisation and returns ``(probe, line)``: the request to send, which must
        change nothing on the board, and the reply line (without its line ending) that
        answers it and nothing else. Make it fresh each time where the firmware allows
        (an echo of a nonce), so that even a late answer to an earlier probe cannot be
        mistaken for it. The first exchange or send on a dirty link then sends ``probe``
        and discards whole lines up to and including ``line`` (a ``\r`` before the
        ``\n`` is ignored), for at most ``drain_limit`` seconds. The board answers in
        order, so every reply owed to an earlier request has been discarded by then.
        """
        self._resync_line = make
        self._resync = None

    # -- requests ------------------------------------------------------------------------

    async def send(
        self,
        data: bytes,
        *,
        timeout: float | None = None,
        then: Callable[[], None] | None = None,
    ) -> None:
        """Send ``data`` with no reply expected (for example a motor speed command).

        Serialised with the exchanges, and run to completion like them, in the caller's
        task: a cancelled caller never leaves a command half sent (a stream sends all of
        it or, torn by ``Task.cancel``, none of it; then ``then`` does not run). It yields
        to the event loop once the bytes have gone, where a cancellation that came
        meanwhile is raised.

        :param then: called once the bytes have gone, even if the caller has been
            cancelled meanwhile (to update what a backend remembers).
        :raises CommunicationTimeoutError: the bytes could not be sent in time.
        :raises BoardDisconnectionError: the port has gone or the link is closed.
        """
        # The hot path of a motor command: the steps are written out here rather than
        # called (each call is a frame more on every command).
        seconds = self._default_timeout if timeout is None else self._timeout(timeout)
        data = bytes(data)
        await anyio.lowlevel.checkpoint_if_cancelled()  # a cancelled caller takes nothing
        await self._lock.acquire()
        try:
            if (
                data
                and self.unconfirmed is None
                and not self._dirty
                and not self._closed
                and self._send_at_once(data)
            ):
                # (a link in step, on a stream that took the bytes with no wait: nothing
                # was awaited, so nothing needed a shield or a deadline)
                if then is not None:
                    then()
            else:
                await self._send_held(data, seconds, then)
        finally:
            self._lock.release()
        # Writing does not wait, so yield here: like every call to the board, a send is a
        # checkpoint, and a loop of sends leaves the event loop (signals, other tasks) room.
        await anyio.lowlevel.checkpoint()

    def _send_at_once(self, data: bytes) -> bool:
        """Write ``data`` if the stream takes it with no wait (lock held, link in step).

        ``False``: nothing was sent (the stream would have to wait).

        :raises BoardDisconnectionError: the port has gone.
        :raises CommunicationError: writing failed (the link is then out of step).
        """
        try:
            sent = self._stream.send_nowait(data)
        except BaseException as exc:
            self._dirty = True  # a stream sends all or nothing, but be safe
            if self._wire.isEnabledFor(TRACE):
                log_wire(self._wire, "->", data)
            if isinstance(exc, _WRITE_ERRORS) and not isinstance(exc, CommunicationError):
                raise self._write_failed(exc, data) from exc
            raise
        if sent and self._wire.isEnabledFor(TRACE):
            log_wire(self._wire, "->", data)
        return sent

    async def _send_held(
        self, data: bytes, seconds: float, then: Callable[[], None] | None
    ) -> None:
        """:meth:`send` with the lock held, when the bytes did not go at once."""
        with anyio.CancelScope(shield=True):
            if self.unconfirmed is not None:
                await self._confirm_locked()
            if self._closed:
                raise BoardDisconnectionError(f"{self._name}: the link is closed")
            finished = False
            try:
                if self._dirty and self._can_resync:
                    await self._resync_locked()
                with anyio.move_on_after(seconds):
                    await self._write(data)
                    finished = True
                if not finished:
                    raise CommunicationTimeoutError(
                        f"{self._name}: could not send {_preview(data)} within {seconds} s"
                    )
            finally:
                if not finished:
                    self._dirty = True
            if then is not None:
                then()

    @overload
    async def exchange(
        self,
        request: bytes,
        reader: ReplyReader[T],
        *,
        timeout: float | None = None,
        when_dirty: Callable[[], tuple[bytes, ReplyReader[T]]] | None = None,
    ) -> T: ...

    @overload
    async def exchange(
        self,
        request: bytes,
        reader: ReplyReader[T],
        *,
        timeout: float | None = None,
        then: Callable[[T], U],
        when_dirty: Callable[[], tuple[bytes, ReplyReader[T]]] | None = None,
    ) -> U: ...

    async def exchange(
        self,
        request: bytes,
        reader: ReplyReader[T],
        *,
        timeout: float | None = None,
        then: Callable[[T], object] | None = None,
        when_dirty: Callable[[], tuple[bytes, ReplyReader[T]]] | None = None,
    ) -> object:
        """Send ``request`` and return the reply that ``reader`` parses.

        Once the link's lock is held, the exchange runs to completion whoever cancels
        the caller (anyio or ``Task.cancel``), with ``timeout`` applying inside, so a
        cancelled caller's exchange still consumes its own reply. A dirty link is first
        cleaned (see the module's notes; this does not count towards ``timeout``).

        :param request: the bytes to send; ``b""`` only reads a reply.
        :param reader: where the reply ends, e.g. :func:`~.readers.read_line`.
        :param timeout: seconds allowed for sending and the whole reply; defaults to
            the link's ``default_timeout``.
        :param then: called with the reply as soon as it has arrived, even if the caller
            has been cancelled meanwhile; its result is returned instead of the reply,
            and its exceptions reach the caller. Parse the reply and update caches here.
        :param when_dirty: for a firmware that can tag a request so that its reply names
            it (a request id): called, with the lock held, only if the link is dirty, it
            returns the tagged request and a correlating reader (see
            :func:`~.readers.matching`) to use instead of ``request`` and ``reader``. A
            clean link has no reply outstanding, so the board's next reply answers the
            plain request, which is shorter on the wire; on a dirty link the tagged
            request's reply is found past any late ones, which are skipped, and the link
            is clean again (see the module's notes).
        :raises CommunicationTimeoutError: no complete reply in time; the link becomes dirty.
        :raises UnexpectedReplyError: ``reader`` could not parse what arrived.
        :raises BoardDisconnectionError: the port has gone or the link is closed.
        :raises CommunicationError: the line never went quiet, or the resynchronisation
            probe was not answered.
        """
        seconds = self._default_timeout if timeout is None else self._timeout(timeout)
        request = bytes(request)
        await anyio.lowlevel.checkpoint_if_cancelled()  # a cancelled caller takes nothing
        await self._lock.acquire()
        try:
            if self.unconfirmed is not None:
                await self._confirm_locked()
            deadline = self._write_at_once(request, seconds)
            if deadline is not None:
                return await self._reply_unshielded(request, reader, seconds, then, deadline)
            return await self._exchange_held(request, reader, seconds, then, when_dirty)
        finally:
            self._lock.release()

    async def command(
        self,
        request: bytes,
        reader: ReplyReader[T],
        *,
        timeout: float | None = None,
        then: Callable[[T], object] | None = None,
        when_dirty: Callable[[], tuple[bytes, ReplyReader[T]]] | None = None,
    ) -> None:
        """Send ``request``, a command whose reply only acknowledges it, and check the reply.

        As :meth:`exchange` (the same arguments), but nothing of the reply is returned:
        ``reader`` and ``then`` check it (``then`` raises if the board refused). While
        acknowledgements are confirmed later (inside
        :func:`~j5aio.backends.acknowledgements.acknowledge_later`) and the link is in
        step (not dirty, no late reply owed), it returns as soon as ``request`` has been
        written, and the acknowledgement is read (by the same deadline, ``timeout`` from
        the write) and ``then`` run before the link's next request, at
        :meth:`aclose`, or when the board is made safe. A failure found then is logged
        at once and raised by that next request as
        :class:`~j5aio.errors.EarlierCommandError` (and that request is not sent,
        unless the boards are being made safe). Otherwise it waits for the reply, as
        :meth:`exchange` does.

        :raises CommunicationTimeoutError: the command could not be written in time (or,
            waiting, no reply came in time).
        :raises EarlierCommandError: the previous command's acknowledgement, read now,
            showed that it failed.
        :raises BoardDisconnectionError: the port has gone or the link is closed.
        """
        # A hot path (a motor command through the sync facade): its steps are written out
        # here rather than called.
        seconds = self._default_timeout if timeout is None else self._timeout(timeout)
        request = bytes(request)
        await anyio.lowlevel.checkpoint_if_cancelled()  # a cancelled caller takes nothing
        await self._lock.acquire()
        try:
            if self.unconfirmed is not None:
                await self._confirm_locked()
            if not _LATER_SWITCH.get() or self._dirty or (self._owed and self._owes()):
                deadline = self._write_at_once(request, seconds)
                if deadline is not None:
                    await self._reply_unshielded(request, reader, seconds, then, deadline)
                else:
                    await self._exchange_held(request, reader, seconds, then, when_dirty)
                return
            with anyio.CancelScope(shield=True) as scope:
                # Write the request and note that its acknowledgement is owed.
                if self._closed:
                    raise BoardDisconnectionError(f"{self._name}: the link is closed")
                if self._buffer:
                    self._discard_stale()
                deadline = scope.deadline = asyncio.get_running_loop().time() + seconds
                written = False
                try:
                    await self._write(request)
                    written = True
                finally:
                    if not written:
                        self._dirty = True  # a stream sends all or nothing, but be safe
                self.unconfirmed = _OwedAcknowledgement(request, reader, then, deadline, seconds)
            if scope.cancelled_caught:
                raise CommunicationTimeoutError(
                    f"{self._name}: could not send {_preview(request)} within {seconds} s"
                )
        finally:
            self._lock.release()
        # As a send: a checkpoint, where a cancellation that came meanwhile is raised.
        await anyio.lowlevel.checkpoint()

    async def confirm(self) -> None:
        """Read and check the acknowledgement still owed to the last :meth:`command` now.

        Does nothing when none is owed. The link's next request does this anyway; call
        it to learn of a failure at a moment of your choosing.

        :raises EarlierCommandError: the command had failed.
        :raises BoardDisconnectionError: the port has gone.
        """
        if self.unconfirmed is None:
            return
        await anyio.lowlevel.checkpoint_if_cancelled()  # a cancelled caller takes nothing
        await self._lock.acquire()
        try:
            if self.unconfirmed is not None:
                await self._confirm_locked()
        finally:
            self._lock.release()

    async def _confirm_locked(self) -> None:
        """Read and check the acknowledgement owed to the last command (lock held).

        Runs shielded, by the command's own deadline (with a moment's grace for a reply
        that came in time but is not read yet). A failure is logged, then raised as
        :class:`~j5aio.errors.EarlierCommandError` (a vanished port as
        :class:`~j5aio.errors.BoardDisconnectionError`), unless the boards are being made
        safe: their safe state must still be sent.
        """
        owed = self.unconfirmed
        assert owed is not None
        self.unconfirmed = None
        progress = _Progress()
        progress.deadline = max(owed.deadline, asyncio.get_running_loop().time() + self._quiet_time)
        progress.seconds = owed.seconds
        try:
            with anyio.CancelScope(shield=True):
                reply = await self._finish_reply(owed.request, owed.reader, progress)
                if owed.then is not None:
                    owed.then(reply)
        except BoardDisconnectionError as exc:
            shown = _preview(owed.request)
            raise BoardDisconnectionError(
                f"{exc} (while reading the acknowledgement of the earlier command {shown})"
            ) from exc
        except CommunicationError as exc:
            shown = _preview(owed.request)
            _log.warning("%s: the earlier command %s failed: %s", self._name, shown, exc)
            if making_safe():
                return
            raise EarlierCommandError(
                f"{self._name}: the earlier command {shown} failed, not this one (which "
                f"was not sent): {exc}",
                owed.request,
            ) from exc
        except asyncio.CancelledError:
            _log.debug(
                "%s: the acknowledgement of %s was not read (cancelled)",
                self._name,
                _preview(owed.request),
            )
            raise

    async def _exchange_held(
        self,
        request: bytes,
        reader: ReplyReader[T],
        seconds: float,
        then: Callable[[T], object] | None,
        when_dirty: Callable[[], tuple[bytes, ReplyReader[T]]] | None,
    ) -> object:
        """The body of :meth:`exchange`, with the lock held.

        Cleans the line if need be, then sends ``request`` and reads its reply. (A
        request on a link in step whose stream takes the bytes at once was written by
        the caller, and its reply read by :meth:`_reply_unshielded`.) One scope both
        shields the exchange and times it out: its deadline is set to ``seconds`` from
        when the request goes out, so that it cancels the read (and this raises the
        timeout) if the reply is late.
        """
        # Every request's path that its caller did not take at once (see
        # _write_at_once): the steps are written out here rather than called, and the
        # progress is made only when needed.
        if when_dirty is not None and (self._dirty or (self._owed and self._owes())):
            request, reader = when_dirty()
            request = bytes(request)
        progress: _Progress | None = None
        sent: float | None = None  # the deadline of a request that has gone
        with anyio.CancelScope(shield=True) as scope:
            try:
                if self._closed:
                    raise BoardDisconnectionError(f"{self._name}: the link is closed")
                correlates = reader.correlates
                if not correlates and self._resync_line is not None and self._owed and self._owes():
                    progress = _Progress()
                    reply = await self._bracketed_locked(request, reader, seconds, progress)
                else:
                    finished = False
                    try:
                        if correlates:
                            pass  # foreign replies, late or left over, are recognised
                        elif self._dirty and self._can_resync:
                            await self._resync_locked()
                        elif self._dirty:
                            await self._drain_locked(self._quiet_time, self._drain_limit)
                        if self._buffer and not correlates:
                            self._discard_stale()
                        deadline = scope.deadline = asyncio.get_running_loop().time() + seconds
                        await self._write(request)
                        sent = deadline
                        reply = await self._read_reply(reader, request)
                        # Nothing awaits from here to the end of the scope, so its
                        # deadline cannot fire any more; leaving the scope drops it.
                        finished = True
                        self._dirty = False
                        if self._buffer and not correlates:
                            self._after_reply(request, reader)  # more than the reply came
                    finally:
                        if not finished:
                            self._dirty = True
                            if sent is not None:
                                self._owe(_lines_of(reader))
            except asyncio.CancelledError:
                # Task.cancel broke through the shield (unless this is the scope's
                # own deadline, which the scope catches). Once the request has gone,
                # its reply is read (and ``then`` run) in a task of its own, which
                # the caller waits for before being cancelled; before that, nothing
                # was sent (a stream sends all or, cancelled, nothing).
                if progress is None and sent is not None:
                    progress = _Progress()
                    progress.deadline, progress.seconds = sent, seconds
                if (
                    progress is not None
                    and progress.deadline is not None
                    and not scope.cancel_called
                ):
                    scope.deadline = math.inf  # the task that finishes it keeps time
                    await self._finish_torn(request, reader, progress, then)
                raise
            return reply if then is None else then(reply)
        raise self._timed_out(request, reader, seconds)

    def _write_at_once(self, request: bytes, seconds: float) -> float | None:
        """Write ``request`` at once if the link is in step; return its deadline if so.

        The common case of every request (lock held): a link in step, with nothing to
        clean, on a stream that takes the bytes at once. Its reply is then read with no
        cancel scope (:meth:`_reply_unshielded`), and its deadline is ``seconds`` from
        now. ``None``: nothing was sent, and the request takes the shielded path
        (:meth:`_exchange_held`).
        """
        if not request or self._dirty or self._owed or self._buffer or self._closed:
            return None
        deadline = asyncio.get_running_loop().time() + seconds
        return deadline if self._send_at_once(request) else None

    async def _reply_unshielded(
        self,
        request: bytes,
        reader: ReplyReader[T],
        seconds: float,
        then: Callable[[T], object] | None,
        deadline: float,
    ) -> object:
        """Read the reply to ``request``, written at once on a link in step (lock held).

        No cancel scope: the stream's own timer ends the wait at ``deadline``, and a
        cancellation (anyio's or ``Task.cancel``) that reaches the wait is handled as
        a torn exchange is: the reply is read, and ``then`` run, in a task of its own,
        by the same deadline, while the caller waits; the caller is cancelled once it
        has finished. Nothing is awaited but the reply, so nothing else can be torn.
        """
        finished = False
        try:
            # What _read_reply does, written out with the stream's own deadline (a
            # coroutine fewer on every reply's path).
            while isinstance(reply := self._take_reply(reader, request), _NotYet):
                try:
                    chunk = await self._stream.receive_by(deadline, self._chunk_size)
                except CommunicationError:
                    raise
                except _DISCONNECTION_ERRORS as exc:
                    raise BoardDisconnectionError(
                        f"{self._name}: the port has gone ({exc!r})"
                    ) from exc
                except OSError as exc:
                    raise CommunicationError(f"{self._name}: reading failed: {exc}") from exc
                if chunk is None:
                    raise self._timed_out(request, reader, seconds)
                if self._wire.isEnabledFor(TRACE):
                    log_wire(self._wire, "<-", chunk)
                self._buffer += chunk
            finished = True
        except asyncio.CancelledError:
            finished = True  # the task that finishes it marks the link if it fails
            progress = _Progress()
            progress.deadline, progress.seconds = deadline, seconds
            await self._finish_torn(request, reader, progress, then)
            raise
        finally:
            if not finished:
                self._dirty = True
                self._owe(_lines_of(reader))
        if self._buffer and not reader.correlates:
            self._after_reply(request, reader)  # more than the reply came
        return reply if then is None else then(reply)

    async def _acquire(self) -> None:
        """Take the link's lock; a caller already cancelled (by anyio) takes nothing."""
        await anyio.lowlevel.checkpoint_if_cancelled()
        await self._lock.acquire()

    async def _finish_torn(
        self,
        request: bytes,
        reader: ReplyReader[T],
        progress: _Progress,
        then: Callable[[T], object] | None,
    ) -> None:
        async def finish() -> None:
            reply = await self._finish_reply(request, reader, progress)
            if then is not None:
                then(reply)

        try:
            await run_to_completion(finish)
        except Exception as exc:
            _log.debug("%s: the reply to a cancelled caller's %r: %r", self._name, request, exc)

    async def read(self, reader: ReplyReader[T], *, timeout: float | None = None) -> T:
        """Read what ``reader`` parses without sending anything (a boot banner, say).

        Not shielded: cancelling it loses nothing, since bytes stay buffered until a
        complete reply is parsed. Bytes left over stay buffered for the next read.

        :raises CommunicationTimeoutError: nothing complete arrived in time.
        """
        seconds = self._timeout(timeout)
        await self._acquire()
        try:
            self._check_open()
            if self.unconfirmed is not None:
                await self._confirm_locked()
            with anyio.move_on_after(seconds):
                return await self._read_reply(reader, b"")
            raise CommunicationTimeoutError(
                f"{self._name}: nothing matching {reader.describe()} arrived within "
                f"{seconds} s (received so far: {_preview(self._buffer)})"
            )
        finally:
            self._lock.release()

    async def read_line(self, *, timeout: float | None = None, terminator: bytes = b"\n") -> bytes:
        """Read one line without sending anything; see :meth:`read` and :func:`.read_line`."""
        return await self.read(read_line(terminator), timeout=timeout)

    async def drain(self, quiet_time: float | None = None, *, limit: float | None = None) -> int:
        """Discard input until the line has been quiet for ``quiet_time`` seconds.

        Also clears the dirty mark, and forgets the replies owed by requests that timed
        out (they are taken to have come, or to be lost). Returns how many bytes were
        discarded.

        :param quiet_time: seconds of silence to wait for; defaults to the link's.
        :param limit: the most seconds to spend; defaults to the link's ``drain_limit``.
        :raises CommunicationError: the line was still busy after ``limit`` seconds.
        """
        quiet = self._quiet_time if quiet_time is None else quiet_time
        bound = self._drain_limit if limit is None else limit
        _check_duration("quiet_time", quiet)
        _check_duration("limit", bound)
        await self._acquire()
        try:
            self._check_open()
            if self.unconfirmed is not None:
                await self._confirm_locked()
            discarded = await self._drain_locked(quiet, bound)
            self._owed = 0
            return discarded
        finally:
            self._lock.release()

    def send_now(self, data: bytes, *, timeout: float | None = None) -> None:
        """Send ``data`` at once, synchronously, bypassing the lock (the safe state at exit).

        For the safety net (:mod:`j5aio.lifetime`): it needs no running event loop. It
        does not wait for an exchange in progress, so the link is marked dirty: a reply
        that such an exchange was waiting for is drained, not taken for another. Output
        still queued may be dropped (see :meth:`.ByteStream.send_now`). Call it from the
        thread that runs the link's event loop, or once that loop has stopped.

        :raises CommunicationError: the bytes could not be sent within ``timeout``
            (the link's ``default_timeout`` if not given).
        :raises BoardDisconnectionError: the port has gone or the link is closed.
        """
        seconds = self._timeout(timeout)
        data = bytes(data)
        self._check_open()
        self._dirty = True
        self._drop_unconfirmed("bytes were sent at once")
        log_wire(self._wire, "->", data)
        try:
            self._stream.send_now(data, seconds)
        except CommunicationError:
            raise
        except OSError as exc:
            raise CommunicationError(
                f"{self._name}: sending {_preview(data)} failed: {exc}"
            ) from exc

    # -- closing -------------------------------------------------------------------------

    def close_now(self) -> None:
        """Close the link and its stream at once, synchronously; idempotent.

        Waiting callers get :class:`~j5aio.errors.BoardDisconnectionError`.
        """
        if not self._closed:
            self._drop_unconfirmed("the link was closed at once")
        self._closed = True
        self._stream.close_now()

    def _drop_unconfirmed(self, why: str) -> None:
        """Give up reading the acknowledgement owed, if any (a resync discards it)."""
        if self.unconfirmed is not None:
            _log.warning(
                "%s: the acknowledgement of %s was not checked: %s",
                self._name,
                _preview(self.unconfirmed.request),
                why,
            )
            self.unconfirmed = None

    async def aclose(self) -> None:
        """Close the link and its stream, letting queued output go first; idempotent.

        An acknowledgement still owed (see :meth:`command`) is read and checked first; a
        failure is logged, not raised.
        """
        with anyio.CancelScope(shield=True):
            if self.unconfirmed is not None and not self._closed:
                await self._lock.acquire()
                try:
                    if self.unconfirmed is not None:
                        await self._confirm_locked()
                except CommunicationError:
                    pass  # logged as it was read; a board being closed has nothing to tell
                finally:
                    self._lock.release()
            self._closed = True
            await self._stream.aclose()

    def __repr__(self) -> str:
        state = "closed" if self._closed else ("dirty" if self._dirty else "open")
        return f"<SerialLink {self._name!r} {state}>"

    # -- internals (all called with the lock held) -------------------------------------

    def _timeout(self, timeout: float | None) -> float:
        if timeout is None:
            return self._default_timeout
        return _check_duration("timeout", timeout)

    def _check_open(self) -> None:
        if self._closed:
            raise BoardDisconnectionError(f"{self._name}: the link is closed")

    async def _bracketed_locked(
        self, request: bytes, reader: ReplyReader[T], seconds: float, progress: _Progress
    ) -> T:
        """Exchange between two probes, while a reply that timed out may still come.

        Sent as ``probe, request, probe``: lines before the first probe's answer are
        late replies, and the reply is the one thing between the two answers. A late
        reply that arrives between them (it overtook nothing: the board answered it
        late) makes two things there, and which is this request's cannot be told: that
        raises :class:`~j5aio.errors.CommunicationError`, never a wrong answer.
        """
        assert self._resync_line is not None
        opening, opened = self._resync_line()
        closing, closed = self._resync_line()
        progress.bracket = (opened, closed)
        progress.remaining = 2 + _lines_of(reader)  # what this exchange is owed
        finished = False
        # The late lines come first: they get the time a resynchronisation would.
        seconds += self._drain_limit
        if self._buffer:
            # Whole lines here were owed (or noise); a part line is noise (a reply whose
            # line ending was lost) or the start of a late line, whose end still counts.
            self._settle(self._buffer.count(b"\n"))
            self._buffer.clear()
        try:
            with anyio.move_on_after(seconds):
                deadline = anyio.current_time() + seconds
                await self._write(opening + request + closing)
                progress.deadline, progress.seconds = deadline, seconds
                reply = await self._read_bracketed(request, reader, progress)
                finished = True
                return reply
            raise self._timed_out(request, reader, seconds)
        finally:
            # Every line it was owed having come (even amid an ambiguous reply), the
            # link is in step again.
            if not finished and (progress.deadline is None or progress.remaining > 0):
                self._dirty = True
                if progress.deadline is not None:
                    self._owe(progress.remaining)

    async def _read_bracketed(
        self, request: bytes, reader: ReplyReader[T], progress: _Progress
    ) -> T:
        """Read a bracketed exchange's answers and reply, from where it had got to."""
        assert progress.bracket is not None
        opened, closed = progress.bracket
        if not progress.opened:
            await self._skip_to_line(opened)
            progress.opened = True
            progress.remaining -= 1
        if not progress.replied:
            progress.reply = await self._read_reply(reader, request)
            progress.replied = True
            progress.remaining -= _lines_of(reader)
        extra = await self._skip_to_line(closed)
        progress.remaining -= 1
        self._dirty = bool(self._buffer)
        if extra:
            raise CommunicationError(
                f"{self._name}: a late reply to an earlier request came amid the reply to "
                f"{_preview(request)}; which is which cannot be told, so neither is used"
            )
        reply: T = progress.reply
        return reply

    async def _skip_to_line(self, answer: bytes) -> int:
        """Discard whole lines up to and including the line ``answer``; return how many.

        Each line discarded was owed by a request that timed out (or is noise).
        """
        skipped = 0
        while True:
            discard, length, lines = self._find_line(answer)
            del self._buffer[:discard]
            skipped += lines
            self._settle(lines)
            if length >= 0:
                del self._buffer[:length]
                return skipped
            self._buffer += await self._receive()

    def _owe(self, replies: int) -> None:
        """Note that ``replies`` replies (lines, on a line protocol) may still come, late."""
        if replies > 0:
            self._owed += replies
            self._owed_until = anyio.current_time() + self._late_limit

    def _settle(self, replies: int) -> None:
        """Note that ``replies`` owed by earlier requests have come (and gone)."""
        self._owed = max(0, self._owed - replies)

    def _owes(self) -> bool:
        """Whether a late reply may still come: requests are then bracketed, or tagged."""
        if self._owed and anyio.current_time() >= self._owed_until:
            _log.debug("%s: %d late replies never came", self._name, self._owed)
            self._owed = 0
        return self._owed > 0

    async def _finish_reply(self, request: bytes, reader: ReplyReader[T], progress: _Progress) -> T:
        """Read the reply to ``request`` (already sent) by the exchange's deadline."""
        assert progress.deadline is not None
        finished = False
        try:
            with anyio.move_on_after(max(0.0, progress.deadline - anyio.current_time())):
                if progress.bracket is not None:
                    try:
                        return await self._read_bracketed(request, reader, progress)
                    finally:
                        finished = progress.remaining <= 0
                reply = await self._read_reply(reader, request)
                finished = True
                self._dirty = False
                if self._buffer and not reader.correlates:
                    self._after_reply(request, reader)  # more than the reply came
                return reply
            raise self._timed_out(request, reader, progress.seconds)
        finally:
            if not finished:
                self._dirty = True
                self._owe(progress.remaining if progress.bracket else _lines_of(reader))

    def _after_reply(self, request: bytes, reader: ReplyReader[Any]) -> None:
        """Mark the link dirty: bytes came after the reply to ``request``.

        The line was clean when the exchange began (drained, resynchronised, or
        correlated), so it is dirty now only if more than the reply came; a correlating
        reader skips whatever it is, so its callers do not call this.
        """
        _log.debug(
            "%s: reply to %r followed by %s; the next exchange drains first",
            self._name,
            request,
            _preview(self._buffer),
        )
        self._dirty = True

    def _timed_out(
        self, request: bytes, reader: ReplyReader[Any], seconds: float
    ) -> CommunicationTimeoutError:
        return CommunicationTimeoutError(
            f"{self._name}: no complete reply ({reader.describe()}) to {_preview(request)} "
            f"within {seconds:g} s (received so far: {_preview(self._buffer)})"
        )

    @property
    def _can_resync(self) -> bool:
        return self._resync is not None or self._resync_line is not None

    async def _resync_locked(self) -> None:
        """Send the probe and discard input up to and including its known answer."""
        if self._resync_failed:
            # The answer to the last probe never came in time, and may still come; a
            # fixed answer would then be mistaken for the next probe's. Let it pass first.
            await self._drain_locked(self._quiet_time, self._drain_limit)
            self._dirty = True
        if self._resync_line is not None:
            probe, answer = self._resync_line()
            find: Callable[[], tuple[int, int, int]] = lambda: self._find_line(answer)  # noqa: E731
        else:
            assert self._resync is not None
            probe, answer = self._resync
            find = lambda: self._find_bytes(answer)  # noqa: E731
        discarded = 0
        self._resync_failed = True
        with anyio.move_on_after(self._drain_limit):
            await self._write(probe)
            while True:
                skipped, end, lines = find()
                discarded += skipped
                del self._buffer[:skipped]
                self._settle(lines)
                if end >= 0:
                    break
                self._buffer += await self._receive()
            del self._buffer[:end]
            _log.debug(
                "%s: resynchronised with %r (discarded %d stale bytes)",
                self._name,
                probe,
                discarded,
            )
            self._dirty = False
            self._resync_failed = False
            return
        raise CommunicationError(
            f"{self._name}: could not resynchronise with the board: its answer {answer!r} "
            f"to {probe!r} did not come within {self._drain_limit} s"
        )

    def _find_bytes(self, answer: bytes) -> tuple[int, int, int]:
        """Return (bytes to discard, length of ``answer`` after them or -1, lines in them)."""
        found = self._buffer.find(answer)
        discard = found if found >= 0 else max(len(self._buffer) - len(answer) + 1, 0)
        return discard, len(answer) if found >= 0 else -1, self._buffer.count(b"\n", 0, discard)

    def _find_line(self, answer: bytes) -> tuple[int, int, int]:
        """Return (bytes of whole lines to discard, length of the line ``answer`` or -1, lines).

        The bytes to discard are the lines before the answer line if it has come (its
        length, ending included, is the second number), else every whole line so far.
        """
        start = lines = 0
        while (end := self._buffer.find(b"\n", start)) >= 0:
            line = bytes(self._buffer[start:end]).removesuffix(b"\r")
            if line == answer:
                return start, end + 1 - start, lines
            start = end + 1
            lines += 1
        return start, -1, lines

    async def _read_reply(self, reader: ReplyReader[T], request: bytes) -> T:
        """Read what ``reader`` parses (the caller bounds the time)."""
        while isinstance(reply := self._take_reply(reader, request), _NotYet):
            self._buffer += await self._receive()
        return reply

    def _take_reply(self, reader: ReplyReader[T], request: bytes) -> T | _NotYet:
        """Take what ``reader`` parses out of the buffer, or :data:`_NOT_YET` if incomplete."""
        try:
            parsed: tuple[T, int] | tuple[T, int, int] | None
            # (``correlates`` first: a class attribute, where ``isinstance`` of an
            # abstract class is a call on every reply.)
            if reader.correlates and _is_matching_reader(reader):
                parsed = reader.parse_counting(self._buffer)
            else:
                parsed = reader.parse(self._buffer)
        except UnexpectedReplyError as exc:
            raise self._unparseable(request, exc) from exc
        if parsed is None:
            return _NOT_YET
        reply: T = parsed[0]
        used = parsed[1]
        if len(parsed) > 2:
            self._settle(parsed[2])  # foreign replies skipped: late ones, come
        del self._buffer[:used]
        return reply

    def _unparseable(self, request: bytes, exc: UnexpectedReplyError) -> UnexpectedReplyError:
        """Drop what a reader refused, and say so (the error to raise for it).

        What the reader refused (line noise, an over-long line) is never part of a good
        reply: it is dropped, or every later request fails on the same bytes. The link
        is dirty now, so what follows is resynchronised.
        """
        _log.debug("%s: discarding unparseable %s", self._name, _preview(self._buffer))
        self._buffer.clear()
        about = f" to {_preview(request)}" if request else ""
        return UnexpectedReplyError(f"{self._name}: bad reply{about}: {exc}")

    async def _drain_locked(self, quiet: float, bound: float) -> int:
        discarded = len(self._buffer)
        self._settle(self._buffer.count(b"\n"))
        self._buffer.clear()
        deadline = anyio.current_time() + bound
        while True:
            with anyio.move_on_after(quiet) as silence:
                chunk = await self._receive()
                discarded += len(chunk)
                self._settle(chunk.count(b"\n"))
            if silence.cancelled_caught:
                break
            if anyio.current_time() >= deadline:
                self._dirty = True
                raise CommunicationError(
                    f"{self._name}: the board kept sending for {bound} s; could not find a "
                    f"quiet moment to start the next request (discarded {discarded} bytes)"
                )
        if discarded:
            _log.debug("%s: drained %d bytes of stale input", self._name, discarded)
        self._dirty = False
        return discarded

    async def _write(self, data: bytes) -> None:
        """Write ``data``, logged on the wire trace (an empty request is logged, not sent)."""
        if self._wire.isEnabledFor(TRACE):
            log_wire(self._wire, "->", data)
        if not data:
            return
        try:
            # The caller holds the lock, shielded, past its own cancellation check: the
            # bytes go at once where the stream can take them, with no second check.
            if not self._stream.send_nowait(data):
                await self._stream.send(data)
        except CommunicationError:
            raise
        except _WRITE_ERRORS as exc:
            raise self._write_failed(exc, data) from exc

    def _discard_stale(self) -> None:
        """Throw away input received before a request was written (none was asked for)."""
        _log.debug("%s: discarding stale input %s", self._name, _preview(self._buffer))
        self._settle(self._buffer.count(b"\n"))
        self._buffer.clear()

    def _write_failed(self, exc: BaseException, data: bytes) -> CommunicationError:
        """The error that a stream's failure to send ``data`` (``exc``) is raised as."""
        if isinstance(exc, _DISCONNECTION_ERRORS):
            return BoardDisconnectionError(f"{self._name}: the port has gone ({exc!r})")
        return CommunicationError(f"{self._name}: sending {_preview(data)} failed: {exc}")

    async def _receive(self) -> bytes:
        try:
            chunk = await self._stream.receive(self._chunk_size)
        except CommunicationError:
            raise
        except _DISCONNECTION_ERRORS as exc:
            raise BoardDisconnectionError(f"{self._name}: the port has gone ({exc!r})") from exc
        except OSError as exc:
            raise CommunicationError(f"{self._name}: reading failed: {exc}") from exc
        if self._wire.isEnabledFor(TRACE):
            log_wire(self._wire, "<-", chunk)
        return chunk

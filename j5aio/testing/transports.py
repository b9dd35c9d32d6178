r"""Fake transports for testing backends: record, script and break byte streams.

In the spirit of httpx's ``MockTransport``, these are
:class:`~j5aio.backends.hardware.transports.stream.ByteStream` objects that a test hands to a
backend in place of a serial port, usually through
:meth:`SerialHardwareBackend.from_stream
<j5aio.backends.hardware.serial_backend.SerialHardwareBackend.from_stream>`, which runs
the backend's handshake over the stream and returns its board:

* :class:`ScriptedStream` answers a fixed script of requests, and fails the test with a
  clear diff when the backend sends something else::

      stream = ScriptedStream([(b"?\n", b"BEE:2.1\n"), (b"L1\n", b"OK\n")])
      board = await BeeBackend.from_stream(stream, port="script", serial_number="B1")
      await board.led.set_state(True)
      stream.assert_all_used()

  (A backend can also be built on a link by hand: ``MyBackend(SerialLink(stream,
  name="script"), port="script")``; its ``port=`` is required.)

* :class:`RecordingStream` wraps any stream and records every chunk both ways.
* :class:`FaultyStream` wraps any stream and injects faults, on demand or on a schedule:
  a delayed (in order, or overtaken by later replies), dropped or corrupted reply, a
  disconnection, or a board gone silent.
"""

from __future__ import annotations

import enum
import time
from collections import deque
from collections.abc import Awaitable, Callable, Iterable, Mapping
from dataclasses import dataclass
from typing import Literal, TypeVar

import anyio
import anyio.lowlevel

from j5aio.backends.hardware.transports._inbox import Inbox
from j5aio.backends.hardware.transports.stream import ByteStream
from j5aio.errors import BoardDisconnectionError

__all__ = [
    "Fault",
    "FaultKind",
    "FaultyStream",
    "RecordingStream",
    "ScriptedStream",
    "WireEvent",
    "WrappingStream",
    "flip_first_byte",
]

T = TypeVar("T")


class WrappingStream(ByteStream):
    """A stream that stands in front of another: everything goes on to ``inner``.

    :class:`RecordingStream` and :class:`FaultyStream` are made on it, each changing
    what it needs of the way through.

    :param inner: the stream to wrap (to a simulator, a memory peer, a real port, ...).
    """

    def __init__(self, inner: ByteStream) -> None:
        self._inner = inner

    @property
    def inner(self) -> ByteStream:
        """The wrapped stream."""
        return self._inner

    @property
    def name(self) -> str:
        """The wrapped stream's name."""
        return self._inner.name

    @property
    def is_closed(self) -> bool:
        """Whether the wrapped stream is closed."""
        return self._inner.is_closed

    async def send(self, data: bytes) -> None:
        """Send through the wrapped stream."""
        await self._inner.send(data)

    async def receive(self, max_bytes: int = 4096) -> bytes:
        """Receive from the wrapped stream."""
        return await self._inner.receive(max_bytes)

    def send_now(self, data: bytes, timeout: float) -> None:
        """Send through the wrapped stream synchronously."""
        self._inner.send_now(data, timeout)

    def close_now(self) -> None:
        """Close the wrapped stream."""
        self._inner.close_now()

    async def aclose(self) -> None:
        """Close the wrapped stream."""
        await self._inner.aclose()


# -- recording ---------------------------------------------------------------------------


@dataclass(frozen=True)
class WireEvent:
    """One chunk that crossed a :class:`RecordingStream`."""

    #: ``"sent"`` (host to board) or ``"received"`` (board to host).
    direction: Literal["sent", "received"]
    #: The bytes of the chunk.
    data: bytes
    #: When it crossed, from :func:`time.monotonic`.
    time: float


class RecordingStream(WrappingStream):
    """Wraps a stream and records every chunk sent and received, with timestamps."""

    def __init__(self, inner: ByteStream) -> None:
        super().__init__(inner)
        #: Every chunk, in the order it crossed.
        self.events: list[WireEvent] = []

    @property
    def sent(self) -> bytes:
        """Everything sent so far, joined."""
        return b"".join(e.data for e in self.events if e.direction == "sent")

    @property
    def received(self) -> bytes:
        """Everything received so far, joined."""
        return b"".join(e.data for e in self.events if e.direction == "received")

    def clear(self) -> None:
        """Forget what has been recorded."""
        self.events.clear()

    async def send(self, data: bytes) -> None:
        """Send through the wrapped stream and record ``data`` (once it was accepted)."""
        await self._inner.send(data)
        self.events.append(WireEvent("sent", bytes(data), time.monotonic()))

    async def receive(self, max_bytes: int = 4096) -> bytes:
        """Receive from the wrapped stream and record what arrived."""
        data = await self._inner.receive(max_bytes)
        self.events.append(WireEvent("received", data, time.monotonic()))
        return data

    def send_now(self, data: bytes, timeout: float) -> None:
        """Send through the wrapped stream synchronously, and record ``data``."""
        self._inner.send_now(data, timeout)
        self.events.append(WireEvent("sent", bytes(data), time.monotonic()))


# -- fault injection ---------------------------------------------------------------------


class FaultKind(enum.Enum):
    """What a :class:`Fault` does."""

    #: Hold the next reply (and everything after it) back for a while.
    DELAY = "delay"
    #: Hold the next reply back for a while, letting later replies overtake it.
    HOLD = "hold"
    #: Throw the next reply away.
    DROP = "drop"
    #: Pass the next reply through a function that damages it.
    CORRUPT = "corrupt"
    #: The board vanishes: every send and receive raises BoardDisconnectionError.
    DISCONNECT = "disconnect"
    #: The board stops talking and listening: sends are swallowed, replies dropped.
    SILENCE = "silence"


def flip_first_byte(reply: bytes) -> bytes:
    """Invert every bit of the first byte: the default damage of :meth:`Fault.corrupt`."""
    if not reply:
        return reply
    return bytes([reply[0] ^ 0xFF]) + reply[1:]


@dataclass(frozen=True)
class Fault:
    """A fault for :class:`FaultyStream`; make one with the class methods."""

    kind: FaultKind
    #: For DELAY: how long to hold the reply back, in seconds.
    seconds: float = 0.0
    #: For DELAY, DROP and CORRUPT: the bytes that end a reply, or ``None`` for "the
    #: next chunk received".
    terminator: bytes | None = b"\n"
    #: For CORRUPT: the damage done to the reply.
    corrupter: Callable[[bytes], bytes] = flip_first_byte

    @classmethod
    def delay(cls, seconds: float) -> Fault:
        """Hold the next chunk received (and all after it) back for ``seconds``."""
        if seconds < 0:
            raise ValueError(f"a delay cannot be negative, not {seconds}")
        return cls(FaultKind.DELAY, seconds=seconds, terminator=None)

    @classmethod
    def hold(cls, seconds: float, terminator: bytes | None = b"\n") -> Fault:
        """Hold the next reply (bytes up to ``terminator``) back for ``seconds``.

        Unlike :meth:`delay`, replies after it are not held: they overtake it, and it
        arrives out of order (as from a firmware that answers some requests later).
        """
        if seconds < 0:
            raise ValueError(f"a delay cannot be negative, not {seconds}")
        return cls(FaultKind.HOLD, seconds=seconds, terminator=terminator)

    @classmethod
    def drop(cls, terminator: bytes | None = b"\n") -> Fault:
        """Throw away the next reply: bytes up to ``terminator`` (or the next chunk)."""
        return cls(FaultKind.DROP, terminator=terminator)

    @classmethod
    def corrupt(
        cls,
        corrupter: Callable[[bytes], bytes] = flip_first_byte,
        terminator: bytes | None = b"\n",
    ) -> Fault:
        """Damage the next reply (terminator included) with ``corrupter``."""
        return cls(FaultKind.CORRUPT, terminator=terminator, corrupter=corrupter)

    @classmethod
    def disconnect(cls) -> Fault:
        """Make the board vanish."""
        return cls(FaultKind.DISCONNECT)

    @classmethod
    def silence(cls) -> Fault:
        """Make the board stop listening and answering (until :meth:`FaultyStream.resume`)."""
        return cls(FaultKind.SILENCE)


class FaultyStream(WrappingStream):
    """Wraps a stream and injects faults, on demand or by a schedule.

    :param inner: the stream to wrap (to a simulator, a memory peer, a real port, ...).
    :param schedule: faults to inject when a given send happens, keyed by the number of
        the send, counting from 0: ``{3: Fault.drop()}`` drops the reply to the fourth
        request. A DISCONNECT or SILENCE fault applies to the send it is keyed by.

    A synchronous send (:meth:`WrappingStream.send_now`) goes straight on: no fault applies to it.
    """

    def __init__(
        self,
        inner: ByteStream,
        *,
        schedule: Mapping[int, Fault | Iterable[Fault]] | None = None,
    ) -> None:
        super().__init__(inner)
        self._schedule: dict[int, list[Fault]] = {}
        for index, faults in (schedule or {}).items():
            self._schedule[index] = [faults] if isinstance(faults, Fault) else list(faults)
        self._sends = 0
        self._armed: deque[Fault] = deque()
        self._current: Fault | None = None
        self._collected = bytearray()
        self._ready = bytearray()
        self._release_at = 0.0
        self._held: list[tuple[float, bytes]] = []  # (when it is released, the reply)
        self._silent = False
        self._disconnected = False
        self._wait_scope: anyio.CancelScope | None = None

    @property
    def sends(self) -> int:
        """How many sends there have been (the key of the next scheduled fault)."""
        return self._sends

    @property
    def is_disconnected(self) -> bool:
        """Whether a DISCONNECT fault has been injected."""
        return self._disconnected

    @property
    def is_silent(self) -> bool:
        """Whether the board is silenced."""
        return self._silent

    def inject(self, fault: Fault) -> None:
        """Inject ``fault`` now: DISCONNECT and SILENCE at once, others for the next reply."""
        if fault.kind is FaultKind.DISCONNECT:
            self._disconnected = True
            self._interrupt_wait()
        elif fault.kind is FaultKind.SILENCE:
            self._silent = True
        else:
            self._armed.append(fault)

    def delay_next_reply(self, seconds: float) -> None:
        """Hold the next chunk received (and all after it) back for ``seconds``."""
        self.inject(Fault.delay(seconds))

    def hold_next_reply(self, seconds: float, terminator: bytes | None = b"\n") -> None:
        """Hold the next reply back for ``seconds``, letting later replies overtake it."""
        self.inject(Fault.hold(seconds, terminator))

    def drop_next_reply(self, terminator: bytes | None = b"\n") -> None:
        """Throw away the next reply (bytes up to ``terminator``, or the next chunk)."""
        self.inject(Fault.drop(terminator))

    def corrupt_next_reply(
        self,
        corrupter: Callable[[bytes], bytes] = flip_first_byte,
        terminator: bytes | None = b"\n",
    ) -> None:
        """Damage the next reply with ``corrupter`` (by default, invert its first byte)."""
        self.inject(Fault.corrupt(corrupter, terminator))

    def disconnect(self) -> None:
        """Make the board vanish: a waiting receive and every later call raise."""
        self.inject(Fault.disconnect())

    def silence(self) -> None:
        """Make the board stop listening and answering."""
        self.inject(Fault.silence())

    def resume(self) -> None:
        """End a silence; the board listens and answers again."""
        self._silent = False

    async def send(self, data: bytes) -> None:
        """Pass ``data`` on, unless a fault says otherwise."""
        await anyio.lowlevel.checkpoint()
        for fault in self._schedule.pop(self._sends, []):
            self.inject(fault)
        self._sends += 1
        self._check_connected()
        if self._silent:
            return
        await self._inner.send(data)

    async def receive(self, max_bytes: int = 4096) -> bytes:
        """Receive from the wrapped stream, applying the armed faults."""
        if max_bytes < 1:
            raise ValueError(f"max_bytes must be at least 1, not {max_bytes}")
        await anyio.lowlevel.checkpoint()
        while True:
            self._check_connected()
            self._release_held()
            if self._ready:
                wait = self._release_at - anyio.current_time()
                if wait <= 0:
                    data = bytes(self._ready[:max_bytes])
                    del self._ready[:max_bytes]
                    return data
                await self._interruptible(anyio.sleep(wait))
            else:
                with anyio.move_on_after(self._until_held()):
                    chunk = await self._interruptible(self._inner.receive(max_bytes))
                    if chunk is not None and not self._silent:
                        self._process(chunk)

    def close_now(self) -> None:
        """Close the wrapped stream."""
        self._inner.close_now()
        self._interrupt_wait()

    async def aclose(self) -> None:
        """Close the wrapped stream."""
        self._interrupt_wait()
        await self._inner.aclose()

    # -- internals -------------------------------------------------------------------------

    def _release_held(self) -> None:
        now = anyio.current_time()
        due = [reply for when, reply in self._held if when <= now]
        if due:
            self._held = [(when, reply) for when, reply in self._held if when > now]
            for reply in due:
                self._ready += reply

    def _until_held(self) -> float:
        """Seconds until the next held reply is released (infinite with none)."""
        if not self._held:
            return float("inf")
        return max(0.0, min(when for when, _ in self._held) - anyio.current_time())

    def _check_connected(self) -> None:
        if self._disconnected:
            raise BoardDisconnectionError(
                f"{self.name}: the board has been disconnected (injected fault)"
            )

    async def _interruptible(self, awaitable: Awaitable[T]) -> T | None:
        """Await ``awaitable``; return None if :meth:`_interrupt_wait` cuts it short."""
        result: T | None = None
        scope = self._wait_scope = anyio.CancelScope()
        try:
            with scope:
                result = await awaitable
        finally:
            self._wait_scope = None
        return result

    def _interrupt_wait(self) -> None:
        if self._wait_scope is not None:
            self._wait_scope.cancel()

    def _process(self, chunk: bytes) -> None:
        self._collected += chunk
        while self._collected:
            if self._current is None:
                if not self._armed:
                    self._ready += self._collected
                    self._collected.clear()
                    return
                self._current = self._armed.popleft()
            fault = self._current
            if fault.terminator is None:
                end = len(self._collected)
            else:
                found = self._collected.find(fault.terminator)
                if found < 0:
                    return  # the reply is not complete yet
                end = found + len(fault.terminator)
            reply = bytes(self._collected[:end])
            del self._collected[:end]
            self._current = None
            self._apply(fault, reply)

    def _apply(self, fault: Fault, reply: bytes) -> None:
        if fault.kind is FaultKind.DELAY:
            self._release_at = anyio.current_time() + fault.seconds
            self._ready += reply
        elif fault.kind is FaultKind.HOLD:
            self._held.append((anyio.current_time() + fault.seconds, reply))
        elif fault.kind is FaultKind.CORRUPT:
            self._ready += fault.corrupter(reply)
        # DROP: the reply is simply not passed on.


# -- scripted conversations --------------------------------------------------------------


def _describe_mismatch(step: int, expected: bytes, got: bytes) -> str:
    position = next(
        (i for i, (a, b) in enumerate(zip(expected, got, strict=False)) if a != b),
        min(len(expected), len(got)),
    )
    want = expected[position : position + 1] or b"(end of request)"
    have = got[position : position + 1] or b"(end of data)"
    return (
        f"request {step} does not match the script\n"
        f"  expected: {expected!r}\n"
        f"  got:      {got!r}\n"
        f"  first difference at byte {position}: expected {want!r}, got {have!r}"
    )


class ScriptedStream(ByteStream):
    """A fake board that answers a fixed script of (request, reply) steps.

    Requests may arrive in any number of chunks. A reply of ``b""`` means the board
    answers nothing (a command with no acknowledgement). Anything that strays from the
    script raises :class:`AssertionError` from :meth:`send` with a diff, and is also
    remembered, so that :meth:`assert_all_used` fails the test even if the error was
    caught on the way.

    :param script: the expected requests and the replies to give, in order.
    :param banner: bytes the board sends as soon as the stream is made (a boot banner).
    :param name: the name used in messages.
    """

    def __init__(
        self,
        script: Iterable[tuple[bytes, bytes]],
        *,
        banner: bytes = b"",
        name: str = "scripted",
    ) -> None:
        self._steps: list[tuple[bytes, bytes]] = [(bytes(q), bytes(a)) for q, a in script]
        self._name = name
        self._next = 0
        self._pending = bytearray()
        self._failures: list[str] = []
        self._inbox = Inbox()
        self._closed = False
        self._inbox.feed(banner)

    @property
    def name(self) -> str:
        """The name used in messages."""
        return self._name

    @property
    def is_closed(self) -> bool:
        """Whether the stream has been closed."""
        return self._closed

    @property
    def used(self) -> int:
        """How many steps of the script have been played."""
        return self._next

    @property
    def remaining(self) -> list[tuple[bytes, bytes]]:
        """The steps not played yet."""
        return self._steps[self._next :]

    def assert_all_used(self) -> None:
        """Fail unless every step was played, with no stray or partial request."""
        if self._failures:
            raise AssertionError(f"{self._name}: " + "\n".join(self._failures))
        if self._pending:
            raise AssertionError(
                f"{self._name}: a partial request {bytes(self._pending)!r} was sent; "
                f"the script expected {self._steps[self._next][0]!r}"
            )
        if self._next < len(self._steps):
            unused = ", ".join(repr(q) for q, _ in self.remaining)
            raise AssertionError(
                f"{self._name}: {len(self._steps) - self._next} step(s) of the script were "
                f"never requested: {unused}"
            )

    async def send(self, data: bytes) -> None:
        """Check ``data`` against the script and queue the scripted replies."""
        await anyio.lowlevel.checkpoint()
        if self._closed:
            raise BoardDisconnectionError(f"{self._name}: the stream is closed")
        self._pending += data
        while self._pending:
            if self._next >= len(self._steps):
                self._fail(
                    f"unexpected request {bytes(self._pending)!r}: all "
                    f"{len(self._steps)} step(s) of the script have been played"
                )
            expected, reply = self._steps[self._next]
            got = bytes(self._pending[: len(expected)])
            if not expected.startswith(got):
                self._fail(_describe_mismatch(self._next, expected, bytes(self._pending)))
            if len(got) < len(expected):
                return  # wait for the rest of the request
            del self._pending[: len(expected)]
            self._next += 1
            self._inbox.feed(reply)

    async def receive(self, max_bytes: int = 4096) -> bytes:
        """Return scripted replies; see :meth:`.ByteStream.receive`."""
        return await self._inbox.take(max_bytes)

    def close_now(self) -> None:
        """Close the stream."""
        if not self._closed:
            self._closed = True
            self._inbox.finish(
                BoardDisconnectionError(f"{self._name}: the stream is closed"), discard=True
            )

    def _fail(self, message: str) -> None:
        self._failures.append(message)
        self._pending.clear()
        raise AssertionError(f"{self._name}: {message}")

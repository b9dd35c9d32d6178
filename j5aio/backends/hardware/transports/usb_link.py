"""One :class:`USBLink` per USB device: blocking pyusb transfers on one worker thread.

libusb calls block, so each device gets one dedicated thread that runs its transfers in
the order they were asked for (measured: cheaper than ``anyio.to_thread`` per transfer,
and ordered, which a thread pool is not).

Cancellation: a transfer is a job on the thread's queue with its own future.

* A caller cancelled while its job is still queued removes it: the transfer never runs.
* A caller cancelled once its job has started is released at once; the transfer
  completes on the thread and its result is dropped.
* Results travel only through the job's own future, so they never reach another caller.
* A ``then`` callback given with a transfer runs on the event loop as soon as the
  transfer has succeeded, even if its caller was cancelled meanwhile (anyio or
  ``Task.cancel``): backends update what they remember of the board there, so their
  caches change when, and only when, the board has been told.

Polling: :meth:`USBLink.poll_until` runs one read every so often *on the worker thread*,
between the other transfers, and wakes the event loop only when the read has found what
it looks for (or failed). An idle poll therefore costs one wake-up of one thread and the
transfer itself: no task, no future and no hop back to the loop per read. The thread
waits for its next job or its next read on a *doorbell* (a lock that a new job releases):
a wait that ends because a read is due returns ``False`` rather than raising, and a read
that finds nothing allocates no more than its transfer does (measured in
``bench/bench_button.py``: on a loaded, virtualised machine the code run after a 15 ms
sleep finds its caches cold, so every object an idle poll touches costs microseconds).

A device may ring that doorbell itself (a board simulator does; a pyusb device cannot):
one with an ``add_doorbell(ring)`` method (see :class:`RingingDevice`) calls ``ring()``
whenever what a host polls it for may have changed (its button pressed, its cable
pulled). The link's polls then read at once when rung, and otherwise only every
:data:`RUNG_INTERVAL_FACTOR` intervals: a press still travels through the poll's own read
and check, soon after it happens, at a fraction of the cost. Without that method (a real
board) a poll reads every interval, as asked.

A device that answers at once: a board simulator's transfers are function calls that
never block (see :func:`answers_at_once`). Its link has no worker thread. Each transfer
runs in the event loop, after one checkpoint (so that a cancelled caller's transfer never
runs and other tasks get their turn, as with a hand-off to the thread); a poll reads in
the loop too, waiting between reads on a timer and on the device's doorbell; a
synchronous :meth:`USBLink.control_write_now` from another thread runs in that thread,
after any transfer running in the loop. A simulated kit's robot therefore starts no
thread for its USB boards, and its transfers cost no thread hand-off.

Errors: a pyusb error becomes :class:`~j5aio.errors.USBCommunicationError` naming the
board, with the pyusb exception kept as ``usb_error``. errno 19 (``ENODEV``: unplugged)
becomes :class:`USBDisconnectionError`, which is also a
:class:`~j5aio.errors.BoardDisconnectionError`; a pyusb timeout becomes
:class:`USBTransferTimeoutError`, also a :class:`~j5aio.errors.CommunicationTimeoutError`.
Callers may name what an errno means for one transfer (``errors={32: "..."}``).
"""

from __future__ import annotations

import asyncio
import collections
import contextlib
import errno
import logging
import math
import sys
import threading
import time
from collections.abc import Callable, Mapping
from typing import Any, Final, Generic, Protocol, TypeVar

from anyio.abc import AsyncResource

from j5aio.errors import (
    BoardDisconnectionError,
    CommunicationTimeoutError,
    UnexpectedReplyError,
    USBCommunicationError,
)

from ._at_once import ANSWERS_AT_ONCE, answers_at_once
from .trace import log_wire, wire_logger

__all__ = [
    "ANSWERS_AT_ONCE",
    "CONTROL_REQUEST",
    "MAX_POLL_INTERVAL",
    "READ_REQUEST_TYPE",
    "RUNG_INTERVAL_FACTOR",
    "WRITE_REQUEST_TYPE",
    "RingingDevice",
    "USBDeviceLike",
    "USBDisconnectionError",
    "USBLink",
    "USBTransferTimeoutError",
    "answers_at_once",
]

_log = logging.getLogger(__name__)

#: bmRequestType of an SR board's vendor read (device to host).
READ_REQUEST_TYPE = 0x80
#: bmRequestType of an SR board's vendor write (host to device).
WRITE_REQUEST_TYPE = 0x00
#: bRequest that SR USB boards answer.
CONTROL_REQUEST = 64

#: The longest poll interval, in seconds (a day: far beyond any use, and well within what
#: a thread's timed wait accepts).
MAX_POLL_INTERVAL = 86_400.0

#: How many times longer a poll waits between reads of a device that rings the link's
#: doorbell when it changes (see the module's notes): the reads in between only check that
#: the device is still there, so they can be rare (once in 0.75 s for the power board's
#: 15 ms button poll).
RUNG_INTERVAL_FACTOR = 50

T = TypeVar("T")
_JobT = TypeVar("_JobT", bound="_Job[Any]")


class USBDisconnectionError(USBCommunicationError, BoardDisconnectionError):
    """A USB board has gone away (pyusb errno 19, ``ENODEV``), or its link is closed."""


class USBTransferTimeoutError(USBCommunicationError, CommunicationTimeoutError):
    """A USB transfer did not complete within its timeout."""


class USBDeviceLike(Protocol):
    """The part of a pyusb ``usb.core.Device`` that :class:`USBLink` uses."""

    @property
    def idVendor(self) -> int:  # noqa: N802 - pyusb's name
        """The USB vendor ID."""
        ...

    @property
    def idProduct(self) -> int:  # noqa: N802 - pyusb's name
        """The USB product ID."""
        ...

    @property
    def serial_number(self) -> str | None:
        """The serial number string (reading it talks to the device)."""
        ...

    def ctrl_transfer(
        self,
        bmRequestType: int,  # noqa: N803 - pyusb's name
        bRequest: int,  # noqa: N803
        wValue: int = 0,  # noqa: N803
        wIndex: int = 0,  # noqa: N803
        data_or_wLength: Any = None,  # noqa: N803
        timeout: int | None = None,
    ) -> Any:
        """Run a control transfer: return the data read, or the number of bytes written."""
        ...


class RingingDevice(Protocol):
    """A device (a simulator) that tells the link when what it polls for may have changed."""

    def add_doorbell(self, ring: Callable[[], None]) -> Callable[[], None]:
        """Call ``ring()``, from any thread, whenever a polled read may answer differently.

        That is at every change made outside the host's own transfers that a poll may be
        waiting for (a button pressed or released, the cable pulled). Returns the function
        that stops the calls.
        """
        ...


# The states of a job (plain strings, compared by identity: an enum class would cost
# every start its making, for a thread that a simulated or quiet start never uses).
_QUEUED: Final = "queued"
_RUNNING: Final = "running"
_WITHDRAWN: Final = "withdrawn"


class _Job(Generic[T]):
    """One transfer waiting for, or running on, the worker thread."""

    def __init__(
        self,
        work: Callable[[], T],
        loop: asyncio.AbstractEventLoop,
        future: asyncio.Future[Any],
        then: Callable[[T], object] | None = None,
    ) -> None:
        self.work = work
        self.loop = loop
        self.future = future
        self.then = then
        self._state = _QUEUED
        self._lock = threading.Lock()

    def start(self) -> bool:
        """Claim the job for the thread; False if its caller has withdrawn it."""
        with self._lock:
            if self._state is _WITHDRAWN:
                return False
            self._state = _RUNNING
            return True

    def withdraw(self) -> None:
        """Stop the job from running, if it has not started."""
        with self._lock:
            if self._state is _QUEUED:
                self._state = _WITHDRAWN

    def finish(self, outcome: tuple[bool, Any]) -> None:
        """Hand ``(succeeded, value_or_exception)`` to the waiting caller, if any.

        On success ``then`` runs first, on the event loop, whether or not the caller
        still waits.
        """
        if self.then is None or not outcome[0]:
            _post(self.loop, self.future, outcome)
            return
        with contextlib.suppress(RuntimeError):  # the loop has closed: nobody to tell
            self.loop.call_soon_threadsafe(_then_resolve, self.future, outcome, self.then)


class _PollJob(_Job[T]):
    """A read repeated on the worker thread until ``found`` says its result is the one.

    ``finish`` hands the read that was found (or the failure) to the loop, ``then`` first.
    ``interval`` is checked, and multiplied by ``factor`` (at most to the longest).
    """

    def __init__(
        self,
        work: Callable[[], T],
        found: Callable[[T], bool],
        interval: float,
        loop: asyncio.AbstractEventLoop,
        future: asyncio.Future[Any],
        then: Callable[[T], object] | None,
        factor: int,
    ) -> None:
        if not 0 < interval <= MAX_POLL_INTERVAL:
            raise ValueError(
                "interval must be a positive number of seconds up to "
                f"{MAX_POLL_INTERVAL:g}, not {interval!r}"
            )
        # The fields of a job that a poll uses (it is never started or withdrawn as a job
        # is), set here rather than through ``_Job.__init__``: a wait for a button starts
        # a poll, and this is on its path.
        self.work = work
        self.loop = loop
        self.future = future
        self.then = then
        self.found = found
        self.interval = min(interval * factor, MAX_POLL_INTERVAL)
        #: When the next read is due (``time.monotonic``); the first read runs at once.
        self.due = 0.0
        #: Set by the caller when it stops waiting; read by the thread (a plain flag: the
        #: thread at worst makes one more read, whose result nobody takes).
        self.withdrawn = False


class _NowJob:
    """A transfer whose caller waits synchronously (see :meth:`USBLink.control_write_now`)."""

    def __init__(self, work: Callable[[], Any]) -> None:
        self.work = work
        self.done = threading.Event()
        self.outcome: tuple[bool, Any] = (False, None)

    def start(self) -> bool:
        """Always run: a synchronous caller cannot withdraw."""
        return True

    def finish(self, outcome: tuple[bool, Any]) -> None:
        """Hand the outcome to the waiting caller."""
        self.outcome = outcome
        self.done.set()


class _HerePoll:
    """A poll reading a device that answers at once, in the event loop: its doorbell."""

    def __init__(self, loop: asyncio.AbstractEventLoop) -> None:
        self.loop = loop
        #: Whether the device rang since the last read began (under the link's state lock).
        self.rung = False
        self._waiter: asyncio.Future[None] | None = None

    def ring(self) -> None:
        """The device rang (any thread; the link's state lock is held)."""
        self.rung = True
        waiter = self._waiter
        if waiter is not None:
            with contextlib.suppress(RuntimeError):  # the loop has closed: nobody waits
                self.loop.call_soon_threadsafe(_resolve, waiter, None)

    async def wait(self, delay: float, lock: threading.Lock) -> bool:
        """Wait ``delay`` seconds, or until the device rings; return whether it rang.

        ``lock`` is the link's state lock, under which :meth:`ring` is called.
        """
        waiter: asyncio.Future[None] = self.loop.create_future()
        with lock:
            if self.rung:
                return True
            self._waiter = waiter
        timer = self.loop.call_later(max(delay, 0.0), _resolve, waiter, None)
        try:
            await waiter
        finally:
            timer.cancel()
            with lock:
                self._waiter = None
        return self.rung


def _resolve(future: asyncio.Future[Any], outcome: Any) -> None:
    if not future.done():
        future.set_result(outcome)


class _LinkClosed:
    """The link closed while a poll was running."""


class _CallbackFailed:
    """A ``then`` callback raised ``error`` (which is not a transfer error)."""

    def __init__(self, error: Exception) -> None:
        self.error = error


def _then_resolve(
    future: asyncio.Future[Any], outcome: tuple[bool, Any], then: Callable[[Any], object]
) -> None:
    try:
        then(outcome[1])
    except Exception as exc:
        if future.done():
            _log.debug("a USB transfer's callback failed after its caller left: %r", exc)
        outcome = (False, _CallbackFailed(exc))
    _resolve(future, outcome)


def _post(loop: asyncio.AbstractEventLoop, future: asyncio.Future[Any], outcome: Any) -> None:
    """Resolve ``future`` from another thread; nothing happens if its loop has closed."""
    with contextlib.suppress(RuntimeError):
        loop.call_soon_threadsafe(_resolve, future, outcome)


class USBLink(AsyncResource):
    """Ordered transfers to one USB device on a dedicated worker thread.

    :param device: the pyusb device (or a stand-in with the same shape).
    :param board_name: how errors name the board, e.g. ``"Power Board SRABC1"``.
    :param timeout_ms: the timeout of each transfer, passed to pyusb, in milliseconds.
    """

    def __init__(self, device: USBDeviceLike, *, board_name: str, timeout_ms: int = 1000) -> None:
        if timeout_ms < 1:
            raise ValueError(f"timeout_ms must be at least 1, not {timeout_ms}")
        self._device = device
        self._board_name = board_name
        self._timeout_ms = timeout_ms
        self._closed = False
        self._stopped = False
        self._stop_waiters: list[tuple[asyncio.AbstractEventLoop, asyncio.Future[Any]]] = []
        # Guards _closed, _stopped, _stop_waiters and the queueing of jobs (so that no
        # job is queued behind the stop sentinel even if close_now runs on another
        # thread, and so that one job at a time rings the doorbell).
        self._state_lock = threading.Lock()
        # The jobs asked for, in order (``None``: stop), and the doorbell the thread waits
        # on: held while the thread may sleep, released by whoever queues a job.
        self._jobs: collections.deque[_Job[Any] | _NowJob | _PollJob[Any] | None] = (
            collections.deque()
        )
        self._doorbell = threading.Lock()
        self._doorbell.acquire()
        # The polls the worker thread runs, and when the next is due (only the thread
        # touches these).
        self._polls: list[_PollJob[Any]] = []
        self._poll_due = 0.0
        # Set (under ``_state_lock``) by a device that rings the doorbell; cleared by the
        # thread before the read it causes.
        self._rung = False
        self._wire = wire_logger(f"usb:{board_name}")
        # A simulator's doorbell (see the module's notes); a pyusb device has none.
        add_doorbell = getattr(device, "add_doorbell", None)
        self._stop_ringing: Callable[[], None] | None = (
            add_doorbell(self._ring) if callable(add_doorbell) else None
        )
        self._interval_factor = 1 if self._stop_ringing is None else RUNG_INTERVAL_FACTOR
        self._thread = threading.Thread(
            target=self._run, name=f"j5aio USB {board_name}", daemon=True
        )
        # A device that answers at once has no worker thread: its transfers run where they
        # are asked for, one at a time under this lock (see the module's notes).
        self._here: threading.Lock | None = None
        # The polls reading such a device in the event loop (guarded by ``_state_lock``).
        self._polls_here: list[_HerePoll] = []
        if answers_at_once(device):
            self._here = threading.Lock()
        else:
            self._thread.start()

    @property
    def board_name(self) -> str:
        """The name errors give the board."""
        return self._board_name

    @property
    def device(self) -> USBDeviceLike:
        """The device this link drives."""
        return self._device

    @property
    def is_closed(self) -> bool:
        """Whether the link has been closed."""
        return self._closed

    @property
    def thread(self) -> threading.Thread:
        """The worker thread (exposed so that tests can check it has stopped).

        Never started for a device that answers at once.
        """
        return self._thread

    @property
    def rung(self) -> bool:
        """Whether the device rings the link's doorbell (see :class:`RingingDevice`)."""
        return self._stop_ringing is not None

    # -- transfers -----------------------------------------------------------------------

    async def control_read(
        self,
        w_index: int,
        length: int,
        *,
        w_value: int = 0,
        exact: bool = True,
        errors: Mapping[int, str] | None = None,
    ) -> bytes:
        """Read ``length`` bytes with a vendor control transfer (0x80, request 64).

        :param exact: raise :class:`~j5aio.errors.UnexpectedReplyError` if fewer bytes
            arrive.
        :param errors: messages for specific errnos of this transfer.
        """
        description = f"reading {length} bytes from wIndex {w_index} (wValue {w_value})"

        def transfer() -> bytes:
            data = self._device.ctrl_transfer(
                READ_REQUEST_TYPE, CONTROL_REQUEST, w_value, w_index, length, self._timeout_ms
            )
            return bytes(data)

        reply = await self.call(transfer, description=description, errors=errors)
        log_wire(self._wire, f"<- wIndex={w_index} wValue={w_value}", reply)
        if exact and len(reply) != length:
            raise UnexpectedReplyError(
                f"{self._board_name}: {description} returned {len(reply)} bytes"
            )
        return reply

    async def control_write(
        self,
        w_index: int,
        w_value: int,
        data: bytes = b"",
        *,
        errors: Mapping[int, str] | None = None,
        then: Callable[[], None] | None = None,
    ) -> None:
        """Write with a vendor control transfer (0x00, request 64).

        :param errors: messages for specific errnos of this transfer, such as
            ``{32: "the piezo queue is full: buzzing too fast"}``.
        :param then: called once the board has accepted the write, even if the caller
            has been cancelled meanwhile (see the module's notes).
        """
        payload = bytes(data)
        description = f"writing wIndex {w_index} wValue {w_value} data {payload!r}"
        log_wire(self._wire, f"-> wIndex={w_index} wValue={w_value}", payload)

        def transfer() -> int:
            written: int = self._device.ctrl_transfer(
                WRITE_REQUEST_TYPE, CONTROL_REQUEST, w_value, w_index, payload, self._timeout_ms
            )
            return written

        def accepted(written: int) -> None:
            if written != len(payload):
                raise USBCommunicationError(
                    f"{self._board_name}: {description} wrote only {written} bytes"
                )
            if then is not None:
                then()

        await self.call(transfer, description=description, errors=errors, then=accepted)

    async def poll_control_read(
        self,
        w_index: int,
        length: int,
        found: Callable[[bytes], bool],
        *,
        interval: float,
        w_value: int = 0,
        then: Callable[[bytes], object] | None = None,
    ) -> bytes:
        """Read like :meth:`control_read` now and every ``interval`` s until ``found``.

        The reads run on the worker thread (see :meth:`poll_until`): only the reply that
        ``found`` accepts wakes the event loop, and is returned (and given to ``then``,
        even if the caller has been cancelled meanwhile).

        :raises UnexpectedReplyError: a reply was not ``length`` bytes long.
        """
        description = f"polling {length} bytes from wIndex {w_index} (wValue {w_value})"
        # Bound once: a read that finds nothing runs only this function's few lines and
        # the transfer.
        read = self._device.ctrl_transfer
        setup = (READ_REQUEST_TYPE, CONTROL_REQUEST, w_value, w_index, length, self._timeout_ms)

        def transfer() -> bytes:
            data = bytes(read(*setup))
            if len(data) != length:
                raise UnexpectedReplyError(
                    f"{self._board_name}: {description} returned {len(data)} bytes"
                )
            return data

        if self._here is not None:
            accepted = await self._poll_here(transfer, found, interval, description, None)
            if then is not None:
                then(accepted)
            log_wire(self._wire, f"<- wIndex={w_index} wValue={w_value}", accepted)
            return accepted
        # What :meth:`poll_until` does, inline: this is the start button's path.
        loop = asyncio.get_running_loop()
        future: asyncio.Future[tuple[bool, Any]] = loop.create_future()
        job = self._submit(
            _PollJob(transfer, found, interval, loop, future, then, self._interval_factor)
        )
        try:
            succeeded, value = await future
        finally:
            job.withdrawn = True
        reply: bytes = self._poll_result(succeeded, value, description, None)
        log_wire(self._wire, f"<- wIndex={w_index} wValue={w_value}", reply)
        return reply

    async def read_serial_number(self) -> str | None:
        """Read the device's serial number string (a transfer, so on the worker thread)."""
        return await self.call(
            lambda: self._device.serial_number, description="reading the serial number"
        )

    async def call(
        self,
        work: Callable[[], T],
        *,
        description: str,
        errors: Mapping[int, str] | None = None,
        then: Callable[[T], object] | None = None,
    ) -> T:
        """Run ``work`` on the worker thread, after every transfer asked for before it.

        Any pyusb transfer may be run this way. Exceptions that ``work`` raises become
        :class:`~j5aio.errors.USBCommunicationError` (or one of the subclasses above).

        :param description: what ``work`` does, for error messages.
        :param errors: messages for specific errnos.
        :param then: called on the event loop with ``work``'s result once it has
            succeeded, even if the caller has been cancelled meanwhile; an exception it
            raises reaches the caller.
        """
        if self._here is not None:
            # A device that answers at once: in the loop, after a checkpoint (a cancelled
            # caller's transfer never runs; other tasks get their turn).
            await asyncio.sleep(0)
            value = self._run_here(work, description, errors)
            if then is not None:
                then(value)
            return value
        loop = asyncio.get_running_loop()
        future: asyncio.Future[tuple[bool, Any]] = loop.create_future()
        job = self._submit(_Job(work, loop, future, then))
        try:
            succeeded, value = await future
        except BaseException:
            job.withdraw()
            raise
        result: T = self._result(succeeded, value, description, errors)
        return result

    async def poll_until(
        self,
        work: Callable[[], T],
        found: Callable[[T], bool],
        *,
        interval: float,
        description: str,
        errors: Mapping[int, str] | None = None,
        then: Callable[[T], object] | None = None,
    ) -> T:
        """Run ``work`` on the worker thread now and every ``interval`` s until ``found``.

        The reads take their turn among the other transfers, in order, and the event loop
        is woken only once: with the first result that ``found`` accepts, or the first
        failure. Cancelling the caller stops the reads (one that is running completes;
        its result is dropped unless ``then`` takes it).

        :param work: one read (a transfer), run on the worker thread.
        :param found: called on the worker thread with each result; ``True`` ends the poll.
        :param interval: seconds from the start of one read to the start of the next
            (at most :data:`MAX_POLL_INTERVAL`); :data:`RUNG_INTERVAL_FACTOR` times that
            on a device that rings the link's doorbell, which reads at once when rung.
        :param description: what ``work`` does, for error messages.
        :param errors: messages for specific errnos.
        :param then: called on the event loop with the accepted result, even if the caller
            has been cancelled meanwhile (so that a latched event is never lost).
        :raises ValueError: ``interval`` is not a positive number of seconds up to
            :data:`MAX_POLL_INTERVAL`.
        :raises USBCommunicationError: a read failed (or a subclass, as :meth:`call`).
        """
        if self._here is not None:
            result = await self._poll_here(work, found, interval, description, errors)
            if then is not None:
                then(result)
            return result
        loop = asyncio.get_running_loop()
        future: asyncio.Future[tuple[bool, Any]] = loop.create_future()
        job = self._submit(
            _PollJob(work, found, interval, loop, future, then, self._interval_factor)
        )
        try:
            succeeded, value = await future
        finally:
            job.withdrawn = True
        result = self._poll_result(succeeded, value, description, errors)
        return result

    def _poll_result(
        self, succeeded: bool, value: Any, description: str, errors: Mapping[int, str] | None
    ) -> Any:
        """The reply a poll found; else raise its error, translated."""
        if isinstance(value, UnexpectedReplyError):
            raise value
        if isinstance(value, _LinkClosed):
            raise USBDisconnectionError(
                f"{self._board_name}: the USB link was closed while {description}"
            )
        return self._result(succeeded, value, description, errors)

    def _run_here(
        self,
        work: Callable[[], T],
        description: str,
        errors: Mapping[int, str] | None,
        keep: type[Exception] | tuple[type[Exception], ...] = (),
    ) -> T:
        """Run ``work`` now, in this thread, after any transfer running elsewhere.

        For a device that answers at once. Its exceptions are translated as on the thread,
        but those of the classes in ``keep``.
        """
        assert self._here is not None
        with self._here:
            if self._closed:
                raise USBDisconnectionError(f"{self._board_name}: the USB link is closed")
            try:
                return work()
            except keep:
                raise
            except Exception as exc:
                raise self._translate(exc, description, errors or {}) from exc

    async def _poll_here(
        self,
        work: Callable[[], T],
        found: Callable[[T], bool],
        interval: float,
        description: str,
        errors: Mapping[int, str] | None,
    ) -> T:
        """Poll a device that answers at once in the event loop, as the thread polls.

        ``work`` runs now, then every ``interval`` (times the doorbell's factor), and at
        once when the device rings; the first result ``found`` accepts is returned.
        """
        if not 0 < interval <= MAX_POLL_INTERVAL:
            raise ValueError(
                "interval must be a positive number of seconds up to "
                f"{MAX_POLL_INTERVAL:g}, not {interval!r}"
            )
        interval = min(interval * self._interval_factor, MAX_POLL_INTERVAL)
        loop = asyncio.get_running_loop()
        poll = _HerePoll(loop)
        with self._state_lock:
            self._polls_here.append(poll)
        try:
            await asyncio.sleep(0)  # a checkpoint, as every transfer here has
            due = loop.time()
            rang = False
            while True:
                if self._closed:
                    raise USBDisconnectionError(
                        f"{self._board_name}: the USB link was closed while {description}"
                    )
                poll.rung = False  # before the read: a ring during it reads again
                value = self._run_here(work, description, errors, UnexpectedReplyError)
                try:
                    if found(value):
                        return value
                except UnexpectedReplyError:
                    raise
                except Exception as exc:  # as on the thread: the poll's failure
                    raise self._translate(exc, description, errors or {}) from exc
                if not rang:  # the read that was due: the next is due an interval later
                    now = loop.time()
                    due += interval  # a steady rate, unless the loop fell behind
                    if due <= now:
                        due = now + interval
                rang = await poll.wait(due - loop.time(), self._state_lock)
        finally:
            with self._state_lock:
                self._polls_here.remove(poll)

    def _submit(self, job: _JobT) -> _JobT:
        """Queue ``job`` for the worker thread, unless the link is closed."""
        with self._state_lock:
            if self._closed:
                raise USBDisconnectionError(f"{self._board_name}: the USB link is closed")
            # What ``_queue`` does, inline (a job on every transfer's path).
            self._jobs.append(job)
            if self._doorbell.locked():
                self._doorbell.release()
        return job

    def _ring(self) -> None:
        """The device's doorbell: what a poll reads may have changed (any thread)."""
        with self._state_lock:
            self._rung = True
            if self._doorbell.locked():
                self._doorbell.release()
            for poll in self._polls_here:
                poll.ring()

    def _queue(self, job: _Job[Any] | _NowJob | None) -> None:
        """Queue ``job`` (``None``: stop) and ring the doorbell; hold ``_state_lock``.

        Only holders of ``_state_lock`` release the doorbell, one at a time, and only
        when it is held: it is never released twice, and a thread about to wait on it
        finds it released if a job came since it looked at the queue.
        """
        self._jobs.append(job)
        if self._doorbell.locked():
            self._doorbell.release()

    def _result(
        self, succeeded: bool, value: Any, description: str, errors: Mapping[int, str] | None
    ) -> Any:
        """The value of a job that succeeded; else raise its error, translated."""
        if succeeded:
            return value
        if isinstance(value, _CallbackFailed):
            raise value.error
        raise self._translate(value, description, errors or {}) from value

    def control_write_now(
        self, w_index: int, w_value: int, data: bytes = b"", *, timeout: float
    ) -> None:
        """Write like :meth:`control_write`, synchronously, from any thread (the safe state).

        For the safety net (:mod:`j5aio.lifetime`): no event loop is needed. The transfer
        runs on the worker thread after those already asked for, and the caller waits at
        most ``timeout`` seconds for it.

        :raises USBDisconnectionError: the link is closed or the board has gone.
        :raises USBTransferTimeoutError: the transfer did not finish within ``timeout``.
        :raises USBCommunicationError: the transfer failed.
        """
        payload = bytes(data)
        description = f"writing wIndex {w_index} wValue {w_value} data {payload!r}"
        log_wire(self._wire, f"-> wIndex={w_index} wValue={w_value}", payload)
        job = _NowJob(
            lambda: self._device.ctrl_transfer(
                WRITE_REQUEST_TYPE, CONTROL_REQUEST, w_value, w_index, payload, self._timeout_ms
            )
        )
        if threading.current_thread() is self._thread:  # pragma: no cover - a transfer's own code
            try:
                job.finish((True, job.work()))
            except Exception as exc:
                job.finish((False, exc))
        elif self._here is not None:
            self._run_now_here(job, timeout, description)
        else:
            with self._state_lock:
                if self._closed:
                    raise USBDisconnectionError(f"{self._board_name}: the USB link is closed")
                self._queue(job)
            if not job.done.wait(timeout):
                raise USBTransferTimeoutError(
                    f"{self._board_name}: {description} did not finish within {timeout} s"
                )
        succeeded, value = job.outcome
        if not succeeded:
            raise self._translate(value, description, {}) from value

    def _run_now_here(self, job: _NowJob, timeout: float, description: str) -> None:
        """Run a synchronous caller's transfer in its own thread (no worker thread).

        It waits up to ``timeout`` seconds for a transfer running in the event loop.
        """
        assert self._here is not None
        if not self._here.acquire(timeout=max(timeout, 0.0)):
            raise USBTransferTimeoutError(
                f"{self._board_name}: {description} did not finish within {timeout} s"
            )
        try:
            if self._closed:
                raise USBDisconnectionError(f"{self._board_name}: the USB link is closed")
            try:
                job.finish((True, job.work()))
            except Exception as exc:
                job.finish((False, exc))
        finally:
            self._here.release()

    # -- closing -------------------------------------------------------------------------

    def close_now(self, timeout: float = 2.0) -> None:
        """Stop the worker thread once the transfers already asked for are done.

        Synchronous (no event loop or executor needed, so it works in ``atexit``);
        waits up to ``timeout`` seconds for the thread. Idempotent.
        """
        if self._stopped_here():
            return
        self._request_stop()
        if threading.current_thread() is not self._thread:
            self._thread.join(timeout)

    async def aclose(self) -> None:
        """Stop the worker thread once the transfers already asked for are done."""
        if self._stopped_here():
            return
        loop = asyncio.get_running_loop()
        stopped: asyncio.Future[Any] = loop.create_future()
        with self._state_lock:
            if self._stopped:
                return
            self._stop_waiters.append((loop, stopped))
        self._request_stop()
        await stopped
        # The thread has posted its last word and only returns now: wait for that, so
        # that a closed link never has a live thread.
        self._thread.join(1.0)

    def _stopped_here(self) -> bool:
        """Close a link with no worker thread, at once; whether it was one."""
        here = self._here
        if here is None:
            return False
        with here:  # after any transfer running in the event loop
            if not self._stopped:
                self._request_stop()
                with self._state_lock:
                    for poll in self._polls_here:
                        poll.ring()  # each reads at once, and finds the link closed
                self._end()
            return True

    def _request_stop(self) -> None:
        with self._state_lock:
            if self._closed:
                return
            self._closed = True
            self._queue(None)

    def __repr__(self) -> str:
        state = "closed" if self._closed else "open"
        return f"<USBLink {self._board_name!r} {state}>"

    # -- internals -----------------------------------------------------------------------

    def _run(self) -> None:
        jobs = self._jobs
        doorbell = self._doorbell
        polls = self._polls
        monotonic = time.monotonic
        while True:
            if not jobs:
                if not polls:
                    doorbell.acquire()
                    continue
                if len(polls) == 1:  # the usual case: one button waited for
                    self._poll_alone(polls[0])
                    continue
                wait = self._poll_due - monotonic()
                rung = False
                if wait > 0 and doorbell.acquire(True, wait):
                    if not self._rung:
                        continue  # a job came (or a ring left over from one already run)
                    rung, self._rung = True, False  # before the reads: a later ring reads again
                self._run_due_polls(every=rung)
                continue
            job = jobs.popleft()
            if job is None:
                self._end()
                return
            if isinstance(job, _PollJob):
                self._polls.append(job)  # due at once: its first read runs next
                self._poll_due = 0.0
                self._rung = False  # that read sees any change rung for before it
                continue  # (alone, in ``_poll_alone``; else after the next job)
            elif job.start():
                try:
                    outcome: tuple[bool, Any] = (True, job.work())
                except BaseException as exc:  # the thread must survive, and its caller hear
                    outcome = (False, exc)
                job.finish(outcome)
            if self._polls:
                self._run_due_polls()

    def _end(self) -> None:
        """The link's last steps (its worker thread's, or its closer's if it had none)."""
        for poll in self._polls:
            if not poll.withdrawn:
                poll.finish((False, _LinkClosed()))
        self._polls.clear()
        if self._stop_ringing is not None:
            self._stop_ringing()
        self._release_device()
        with self._state_lock:
            self._stopped = True
            waiters, self._stop_waiters = self._stop_waiters, []
        for loop, future in waiters:
            _post(loop, future, None)

    def _poll_alone(self, poll: _PollJob[Any]) -> None:
        """Run the only poll until a job comes or the poll ends: the idle path.

        An idle poll's whole cost is the wait's wake-up, the read and ``found``: the
        loop keeps what it needs in local variables, raises no exception when a read is
        due (the doorbell's timed wait returns ``False``) and allocates nothing itself.
        """
        jobs, doorbell, monotonic = self._jobs, self._doorbell, time.monotonic
        work, found, interval = poll.work, poll.found, poll.interval
        due = poll.due
        try:
            while not jobs:
                wait = due - monotonic()
                if wait > 0 and doorbell.acquire(True, wait):
                    if not self._rung:
                        continue  # a job came (or a ring left over from one already run)
                    # The device rang: read now, before the read that is due (whose time
                    # stays). Cleared before the read: a ring after it reads again.
                    self._rung = False
                else:
                    now = monotonic()
                    due += interval  # a steady rate, unless the thread fell behind
                    if due <= now:
                        due = now + interval
                if poll.withdrawn:
                    self._polls.clear()
                    return
                try:
                    value = work()
                    if not found(value):
                        continue
                    outcome: tuple[bool, Any] = (True, value)
                except BaseException as exc:  # the thread must survive, and the caller hear
                    outcome = (False, exc)
                self._polls.clear()
                poll.finish(outcome)
                return
        finally:
            poll.due = self._poll_due = due

    def _run_due_polls(self, *, every: bool = False) -> None:
        """Run the polls that are due (``every``: all of them); note when the next is due."""
        now = time.monotonic()
        polls = self._polls
        next_due = math.inf
        # One poll (the usual case) is looked at in place; several, in a copy, since a
        # poll that ends leaves the list.
        for poll in polls if len(polls) == 1 else polls[:]:
            if poll.withdrawn:
                polls.remove(poll)
                continue
            due = poll.due
            if due <= now:
                due += poll.interval  # a steady rate, unless the thread fell behind
                if due <= now:
                    due = now + poll.interval
                poll.due = due
            elif not every:
                if due < next_due:
                    next_due = due
                continue
            try:
                value = poll.work()
                if not poll.found(value):
                    if due < next_due:
                        next_due = due
                    continue
                outcome: tuple[bool, Any] = (True, value)
            except BaseException as exc:  # the thread must survive, and the caller hear
                outcome = (False, exc)
            polls.remove(poll)
            poll.finish(outcome)
        self._poll_due = next_due

    def _release_device(self) -> None:
        # pyusb is looked up, not imported: a real device can only come from it once loaded
        # (a simulated kit's stand-ins never load it).
        core = sys.modules.get("usb.core")
        if core is not None and isinstance(self._device, core.Device):
            import usb.util

            try:
                usb.util.dispose_resources(self._device)
            except Exception as exc:  # pragma: no cover - depends on libusb
                _log.debug("%s: releasing the device failed: %r", self._board_name, exc)

    def _translate(
        self, exc: BaseException, description: str, errors: Mapping[int, str]
    ) -> USBCommunicationError:
        code = getattr(exc, "errno", None)
        detail = getattr(exc, "strerror", None) or str(exc) or type(exc).__name__
        custom = errors.get(code) if isinstance(code, int) else None
        if code == errno.ENODEV:
            return USBDisconnectionError(
                f"{self._board_name}: {custom}"
                if custom
                else f"{self._board_name} has been disconnected ({description}: {detail}). "
                "Check its USB cable and power, then run the program again.",
                exc,
            )
        core = sys.modules.get("usb.core")  # (loaded wherever a pyusb error was raised)
        timed_out = core is not None and isinstance(exc, core.USBTimeoutError)
        if timed_out or code == errno.ETIMEDOUT:
            return USBTransferTimeoutError(
                f"{self._board_name}: {custom}"
                if custom
                else f"{self._board_name} did not answer in time ({description}: {detail})",
                exc,
            )
        if custom:
            return USBCommunicationError(f"{self._board_name}: {custom}", exc)
        return USBCommunicationError(f"{self._board_name}: {description} failed: {detail}", exc)

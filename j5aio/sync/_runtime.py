"""The portal behind the sync facade: one event-loop thread per process.

Every blocking call of the facade hands a coroutine to :func:`call`, which runs it in a
background thread that owns an asyncio event loop, and waits for its result.

Three things matter more than anything else here:

* **Cancellation.** If the waiting thread is interrupted (Ctrl-C, SIGTERM turned into
  ``SystemExit``, any ``BaseException``), the coroutine is cancelled through an anyio
  cancel scope (so shielded transport exchanges stay whole) and the caller waits briefly
  for the cancellation to land before re-raising, so that a motor command cannot complete
  after the program has moved on. A call withdrawn before it started never runs. An
  interrupt that lands just after the call finished finds it finished and does not wait.
* **Exit.** The loop thread is a daemon. The portal's :func:`shutdown` is an exit step of
  the safety net (:mod:`j5aio.lifetime`): when the program ends, every board is made safe
  and its port closed through the loop, the loop stops, and the net then catches any
  board that was left. A beginner who never closes anything still gets a prompt exit.
* **Speed.** One persistent worker task per portal runs the calls one after another, so
  no task and no cancel scope are made per call (the worker's scope is replaced only
  after it has been used to cancel a call), and each calling thread reuses one lock to
  wait on. A call costs two thread wake-ups, both on a futex: while the loop watches no
  file (the simulated kit) it sleeps on a lock rather than in ``epoll``
  (:class:`_ParkingSelector`), the caller rings it, and the loop hands the call to its
  worker in the same turn. The caller is let go just before the loop sleeps again, so
  that it does not then wait for the GIL as well.

While the caller waits it blocks on a lock with no time limit: an idle program (a
beginner's ``wait_until_pressed``) costs no CPU at all, in the caller's thread or in the
loop's. Signals still interrupt the wait at once, because the portal thread (and every
thread it starts: anyio's workers, USB links) blocks SIGINT, SIGTERM and SIGHUP, so the
kernel delivers them to the waiting main thread. A signal can still land on a thread the
program started itself; then Python's signal wake-up file (:func:`signal.set_wakeup_fd`,
when nobody else uses it) tells a small watcher thread, which has the loop release every
waiting caller's lock so that the main thread returns to Python and runs the handler
(:func:`_watch_signals`). On Windows, where a lock wait cannot be interrupted, the caller
waits in slices of :data:`WAIT_SLICE`.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import selectors
import signal
import socket
import sys
import threading
import time
from collections import deque
from collections.abc import Awaitable, Callable, Coroutine, Mapping
from typing import TYPE_CHECKING, Any, Final, ParamSpec, TypeVar

import anyio

from j5aio import lifetime
from j5aio.boards.board import Board
from j5aio.safety import make_all_safe_uncancellably

if TYPE_CHECKING:
    from _typeshed import FileDescriptorLike

__all__ = [
    "CANCEL_GRACE",
    "SHUTDOWN_TIMEOUT",
    "WAIT_SLICE",
    "call",
    "get_loop",
    "shutdown",
]

LOGGER = logging.getLogger(__name__)

P = ParamSpec("P")
T = TypeVar("T")

#: On Windows, how long one wait for a result lasts before checking for Ctrl-C again.
WAIT_SLICE: Final = 0.05
#: How long an interrupted caller waits for its coroutine's cancellation to land.
CANCEL_GRACE: Final = 2.0
#: How long making boards safe in order, and closing them, may each take at exit.
SHUTDOWN_TIMEOUT: Final = 0.5

#: Whether a lock wait is interrupted by signals (POSIX); otherwise wait in slices.
_INTERRUPTIBLE_WAIT: Final = sys.platform != "win32" and hasattr(signal, "pthread_sigmask")
_SIGNALS_FOR_THE_MAIN_THREAD: Final = frozenset(
    getattr(signal, name) for name in ("SIGINT", "SIGTERM", "SIGHUP") if hasattr(signal, name)
)

# The states of a call.
_QUEUED: Final = 0
_RUNNING: Final = 1
_DONE: Final = 2


class _Call:
    """One coroutine handed to the loop thread, and the lock its caller waits on.

    The loop thread sets :attr:`state` to done *before* releasing :attr:`done`, so a
    caller that sees "not done" knows it has not taken the lock yet. The lock may be
    one the caller reuses from call to call (:func:`call` keeps one per thread): a
    caller that leaves early (interrupted) must then give up that lock for a new one.
    """

    __slots__ = ("coro", "done", "error", "result", "state")

    def __init__(self, coro: Coroutine[Any, Any, Any], done: threading.Lock) -> None:
        self.coro = coro
        self.done = done
        self.result: Any = None
        self.error: BaseException | None = None
        self.state = _QUEUED

    def withdraw(self, reason: str) -> None:
        """Finish a call that never started, without running it (loop thread)."""
        self.coro.close()
        self.error = RuntimeError(reason)
        self.state = _DONE
        _release(self.done)


def _new_done_lock() -> threading.Lock:
    """Return a lock that is held, for a caller to wait on until the loop releases it."""
    lock = threading.Lock()
    lock.acquire()
    return lock


class _ParkingSelector(selectors.BaseSelector):
    """A selector whose loop sleeps on a lock while it watches no file descriptor.

    An event loop blocks in :meth:`select` while it has nothing to do. When it watches no
    file of its own (true of the simulated kit, whose boards talk through memory), a
    wake-up through the loop's self-pipe costs a socket write, a return from ``epoll``
    and a socket read; waiting on a :class:`threading.Lock` instead costs one futex wake,
    about half as much. :meth:`ring` wakes the loop the cheap way when it is parked on
    the lock, and through the self-pipe (``write_to_pipe``) when it is in ``epoll``.

    Two hooks let the portal do its own work at the right moment, in the loop thread:
    ``before_wait`` runs each time the loop is about to wait (the portal releases the
    callers of finished calls there, just before the loop thread gives up the GIL, so
    that a woken caller does not wait for the GIL too), and ``after_wait`` runs each time
    the loop returns from a wait (the portal hands a queued call to its worker there).
    """

    _AWAKE: Final = 0
    _PARKED: Final = 1
    _IN_EPOLL: Final = 2

    def __init__(self) -> None:
        self._inner = selectors.DefaultSelector()
        self._mutex = threading.Lock()
        self._bell = _new_done_lock()
        self._mode = self._AWAKE
        self._rung = False
        self.own_files = 1  # the loop's self-pipe, which a parked loop need not watch
        self.write_to_pipe: Callable[[], None] = _nothing
        self.before_wait: Callable[[], None] = _nothing
        self.after_wait: Callable[[], None] = _nothing

    def register(
        self, fileobj: FileDescriptorLike, events: int, data: Any = None
    ) -> selectors.SelectorKey:
        """Watch ``fileobj`` (as :meth:`selectors.BaseSelector.register`)."""
        return self._inner.register(fileobj, events, data)

    def unregister(self, fileobj: FileDescriptorLike) -> selectors.SelectorKey:
        """Stop watching ``fileobj`` (as :meth:`selectors.BaseSelector.unregister`)."""
        return self._inner.unregister(fileobj)

    def modify(
        self, fileobj: FileDescriptorLike, events: int, data: Any = None
    ) -> selectors.SelectorKey:
        """Change what is watched on ``fileobj`` (as :meth:`selectors.BaseSelector.modify`)."""
        return self._inner.modify(fileobj, events, data)

    def get_map(self) -> Mapping[FileDescriptorLike, selectors.SelectorKey]:
        """Return the watched files (as :meth:`selectors.BaseSelector.get_map`)."""
        return self._inner.get_map()

    def close(self) -> None:
        """Close the inner selector."""
        self._inner.close()

    def select(
        self, timeout: float | None = None
    ) -> list[tuple[selectors.SelectorKey, int]]:
        """Wait up to ``timeout`` seconds for files, or for :meth:`ring` while none are watched."""
        self.before_wait()
        try:
            if len(self._inner.get_map()) > self.own_files:
                return self._select_files(timeout)
            if timeout is None or timeout > 0:
                self._park(timeout)
            else:
                self._rung = False
            return []
        finally:
            self.after_wait()

    def _select_files(
        self, timeout: float | None
    ) -> list[tuple[selectors.SelectorKey, int]]:
        with self._mutex:
            if self._rung:
                self._rung = False
                timeout = 0
            self._mode = self._IN_EPOLL
        try:
            return self._inner.select(timeout)
        finally:
            with self._mutex:
                self._mode = self._AWAKE
                self._rung = False

    def _park(self, timeout: float | None) -> None:
        with self._mutex:
            if self._rung:
                self._rung = False
                return
            self._mode = self._PARKED
        bell = self._bell
        bell.acquire(True, -1 if timeout is None else min(timeout, threading.TIMEOUT_MAX))
        with self._mutex:
            self._mode = self._AWAKE
            self._rung = False
            bell.acquire(False)  # a ring that came after a timeout: the bell stays held

    def ring(self) -> None:
        """Wake the loop, or make its next wait return at once (from any thread)."""
        with self._mutex:
            self._rung = True
            mode = self._mode
            if mode == self._PARKED:
                self._mode = self._AWAKE
                self._bell.release()
                return
        if mode == self._IN_EPOLL:
            self.write_to_pipe()


def _nothing() -> None:
    """Do nothing (the default hook of :class:`_ParkingSelector`)."""


class _PortalLoop(asyncio.SelectorEventLoop):
    """The portal's event loop: an asyncio selector loop on a :class:`_ParkingSelector`."""

    def __init__(self, selector: _ParkingSelector) -> None:
        selector.write_to_pipe = super()._write_to_self  # type: ignore[misc]
        super().__init__(selector)
        self.parking = selector

    def _write_to_self(self) -> None:
        # Every wake-up from another thread (call_soon_threadsafe) comes through here.
        self.parking.ring()


#: Whether the portal's loop can park on a lock: asyncio's selector loop on POSIX, as long
#: as it still wakes itself through ``_write_to_self`` (true of Python 3.11 to 3.14).
_CAN_PARK: Final = sys.platform != "win32" and hasattr(
    asyncio.selector_events.BaseSelectorEventLoop, "_write_to_self"
)


class _LoopThread:
    """The background thread, its event loop and its worker; created on first use."""

    def __init__(self) -> None:
        self._queue: deque[_Call] = deque()
        self._finished: list[_Call] = []
        self._current: _Call | None = None
        self._scope: anyio.CancelScope | None = None
        self._waiter: asyncio.Future[None] | None = None
        self._idle = False
        self._stopping = False
        self.loop: asyncio.AbstractEventLoop
        if _CAN_PARK:
            selector = _ParkingSelector()
            self.loop = _PortalLoop(selector)
            selector.before_wait = self._release_finished
            selector.after_wait = self._hand_over
            self._ring: Callable[[], None] = selector.ring
            self._defer_release = True
        else:  # pragma: no cover - Windows
            self.loop = asyncio.new_event_loop()
            self._ring = self._wake_threadsafe
            self._defer_release = False
        ready = threading.Event()
        self.thread = threading.Thread(
            target=self._run, args=(ready,), name="j5aio sync portal", daemon=True,
        )
        self.thread.start()
        ready.wait()

    # -- the loop thread ----------------------------------------------------------------

    def _run(self, ready: threading.Event) -> None:
        if _INTERRUPTIBLE_WAIT:
            # Signals go to the main thread, whose lock wait they interrupt; the threads
            # this one starts inherit the mask.
            signal.pthread_sigmask(signal.SIG_BLOCK, _SIGNALS_FOR_THE_MAIN_THREAD)
        asyncio.set_event_loop(self.loop)
        try:
            self.loop.run_until_complete(self._main(ready))
            self._cancel_remaining_tasks()
            self.loop.run_until_complete(self.loop.shutdown_asyncgens())
        finally:
            self.loop.close()
            self._stopping = True
            self._withdraw_queued()
            self._release_finished()

    def _cancel_remaining_tasks(self) -> None:
        # As asyncio.run does: tasks left (the safety net's watcher among them) end now.
        tasks = asyncio.all_tasks(self.loop)
        for task in tasks:
            task.cancel()
        if tasks:
            self.loop.run_until_complete(asyncio.gather(*tasks, return_exceptions=True))

    async def _main(self, ready: threading.Event) -> None:
        # This task is the loop's root task: anyio ties its worker threads to it, so they
        # stop when it returns.
        ready.set()
        while not self._stopping:
            with anyio.CancelScope() as scope:
                self._scope = scope
                await self._serve(scope)
        self._withdraw_queued()
        self._release_finished()

    def _withdraw_queued(self) -> None:
        while self._queue:
            self._queue.popleft().withdraw(
                "the board call was cancelled: the j5aio sync portal is stopping"
            )

    async def _serve(self, scope: anyio.CancelScope) -> None:
        """Run calls until the portal stops or ``scope`` has cancelled one."""
        # A stop that lands while the worker waits for a call must not let a call start.
        while not scope.cancel_called and not self._stopping:
            request = self._queue.popleft() if self._queue else await self._next()
            if request is None:
                return
            self._current = request
            request.state = _RUNNING
            try:
                request.result = await request.coro
            except BaseException as exc:
                if scope.cancel_called and isinstance(exc, anyio.get_cancelled_exc_class()):
                    request.error = RuntimeError(
                        "the board call was cancelled: the j5aio sync portal is stopping"
                    )
                    raise  # to the scope, which ends here; the next call gets a new one
                request.error = exc
            finally:
                self._current = None
                request.state = _DONE
                if self._defer_release:
                    # Released when the loop next waits: see _ParkingSelector.
                    self._finished.append(request)
                else:  # pragma: no cover - Windows
                    _release(request.done)

    def _release_finished(self) -> None:
        """Let the callers of finished calls go (loop thread, as the loop is about to wait)."""
        finished = self._finished
        while finished:
            _release(finished.pop().done)

    async def _next(self) -> _Call | None:
        while not self._stopping:
            self._idle = True
            if self._queue:  # appended after the check above, before _idle was set
                self._idle = False
                return self._queue.popleft()
            self._waiter = self.loop.create_future()
            try:
                await self._waiter
            finally:
                self._idle = False
                self._waiter = None
            if self._queue and not self._stopping:
                return self._queue.popleft()
        return None

    def _wake(self) -> None:
        waiter = self._waiter
        if waiter is not None and not waiter.done():
            waiter.set_result(None)

    def _hand_over(self) -> None:
        """Wake the idle worker if a call is queued (loop thread, after each wait)."""
        if self._queue:
            self._wake()

    def _let_callers_check_signals(self) -> None:
        """Release the lock of every caller still waiting (loop thread), not marking done.

        Each caller then finds its call not done and waits again, after its thread has
        run any signal handler that was pending (see :func:`_watch_signals`).
        """
        if self._current is not None:
            _release(self._current.done)
        for request in self._queue:
            _release(request.done)

    def _wake_threadsafe(self) -> None:  # pragma: no cover - Windows
        self.loop.call_soon_threadsafe(self._wake)

    def _cancel(self, request: _Call) -> None:
        if request.state == _QUEUED:
            with contextlib.suppress(ValueError):
                self._queue.remove(request)
                request.withdraw("the board call was cancelled before it started")
        elif request is self._current and self._scope is not None:
            self._scope.cancel()

    def _begin_stop(self) -> None:
        self._stopping = True
        if self._current is not None and self._scope is not None:
            self._scope.cancel()
        self._wake()

    # -- other threads --------------------------------------------------------------------

    def submit(
        self, coro: Coroutine[Any, Any, T], done: threading.Lock | None = None
    ) -> _Call:
        """Queue ``coro`` for the worker (from any thread but the loop's).

        ``done`` is the held lock to release when the call has finished (a new one if not
        given); the caller waits on it.
        """
        if self._stopping or self.loop.is_closed():
            coro.close()
            raise _stopped()
        request = _Call(coro, _new_done_lock() if done is None else done)
        self._queue.append(request)
        if self._idle:
            try:
                self._ring()
            except RuntimeError:  # pragma: no cover - Windows: the loop closed meanwhile
                self._take_back(request)
        if self._stopping:  # stopped meanwhile: the loop withdraws it, or we take it back
            self._take_back(request)
        return request

    def _take_back(self, request: _Call) -> None:
        try:
            self._queue.remove(request)
        except ValueError:
            return  # withdrawn by the loop: the caller finds the reason in its error
        request.coro.close()
        raise _stopped() from None

    def wake_callers(self) -> None:
        """Have every waiting caller check for signals (from any thread but the loop's)."""
        with contextlib.suppress(RuntimeError):
            self.loop.call_soon_threadsafe(self._let_callers_check_signals)

    def cancel(self, request: _Call) -> None:
        """Cancel ``request`` (from any thread but the loop's); it finishes soon after."""
        with contextlib.suppress(RuntimeError):
            self.loop.call_soon_threadsafe(self._cancel, request)

    def stop(self, timeout: float) -> None:
        """Stop the loop (from any thread other than the loop's) and join the thread."""
        if self.thread.is_alive():
            with contextlib.suppress(RuntimeError):
                self.loop.call_soon_threadsafe(self._begin_stop)
            self.thread.join(timeout)


def _stopped() -> RuntimeError:
    return RuntimeError(
        "the j5aio sync portal has stopped (the program is exiting); "
        "no more board calls can be made",
    )


def _release(done: threading.Lock) -> None:
    """Release a caller's lock unless it is released already (loop thread only)."""
    # Only the loop thread releases these locks, so "held" cannot change to "released"
    # between the check and the release.
    if done.locked():
        done.release()


_lock = threading.Lock()
_portal: _LoopThread | None = None
#: The socket our signal watcher listens to, once made (see :func:`_start_signal_watch`).
_signal_writer: socket.socket | None = None


def _start_signal_watch() -> None:
    """Make a signal that lands on any thread wake the waiting callers (main thread only).

    The C-level handler of a Python signal handler runs in whichever thread the kernel
    chose, and writes to the signal wake-up file; the handler itself runs only in the
    main thread, which may be blocked in :func:`_wait`. A daemon thread reads that file
    and has the loop release the callers, which costs nothing until a signal comes. If the
    program (or a running asyncio loop) uses the wake-up file already, it is left alone;
    each new portal takes the file back if it is free again.
    """
    global _signal_writer
    if not _INTERRUPTIBLE_WAIT or threading.current_thread() is not threading.main_thread():
        return
    if _signal_writer is None:
        reader, _signal_writer = socket.socketpair()
        _signal_writer.setblocking(False)
        threading.Thread(
            target=_watch_signals, args=(reader,), name="j5aio sync signal watch", daemon=True
        ).start()
    ours = _signal_writer.fileno()
    previous = signal.set_wakeup_fd(ours, warn_on_full_buffer=False)
    if previous not in (-1, ours):  # someone else's: theirs stays
        signal.set_wakeup_fd(previous)


def _watch_signals(reader: socket.socket) -> None:
    """Wake the waiting callers each time a signal comes (the watcher thread)."""
    # Signals are for the main thread; this one only hears of them.
    signal.pthread_sigmask(signal.SIG_BLOCK, _SIGNALS_FOR_THE_MAIN_THREAD)
    with reader:
        while reader.recv(64):
            portal = _portal
            if portal is not None:
                portal.wake_callers()


def _get_portal() -> _LoopThread:
    global _portal
    if _portal is not None:
        return _portal
    with _lock:
        if _portal is None:
            lifetime.install()
            lifetime.add_exit_step(shutdown)
            _start_signal_watch()
            _portal = _LoopThread()
        return _portal


def get_loop() -> asyncio.AbstractEventLoop:
    """Return the portal's event loop, starting its thread if needed."""
    return _get_portal().loop


def call(fn: Callable[P, Awaitable[T]], /, *args: P.args, **kwargs: P.kwargs) -> T:
    """Run ``fn(*args, **kwargs)`` in the portal's loop and return its result.

    If the calling thread is interrupted while waiting, the coroutine is cancelled and the
    interruption is re-raised once the cancellation has landed (or after
    ``CANCEL_GRACE`` seconds).

    :raises RuntimeError: called from inside the portal's own loop (use ``await`` there),
        or the program is exiting and the portal has stopped.
    """
    portal = _portal if _portal is not None else _get_portal()
    if threading.get_ident() == portal.thread.ident:
        raise RuntimeError(
            "a blocking j5aio.sync call was made from async code running in the sync "
            "portal's loop; await the async API (j5aio) there instead",
        )
    coro = fn(*args, **kwargs)
    if not asyncio.iscoroutine(coro):
        raise TypeError(f"{fn!r} did not return a coroutine")
    try:
        done = _per_thread.done
    except AttributeError:
        done = _per_thread.done = _new_done_lock()
    return _wait(portal, portal.submit(coro, done))  # type: ignore[no-any-return]


#: Per calling thread, the held lock its calls wait on (one lock for all its calls).
_per_thread = threading.local()


def _wait(portal: _LoopThread, request: _Call) -> Any:
    done = request.done
    try:
        if _INTERRUPTIBLE_WAIT:
            # A release before the call is done wakes us to run a signal's handler.
            while not done.acquire() or request.state != _DONE:
                pass
        else:  # pragma: no cover - Windows
            while not done.acquire(timeout=WAIT_SLICE) or request.state != _DONE:
                pass
    except BaseException:
        if getattr(_per_thread, "done", None) is done:
            # Whether the loop has released it yet or will later, this lock is spent.
            _per_thread.done = _new_done_lock()
        if request.state != _DONE:  # not finished, so the lock is not ours: cancel, wait
            with lifetime.quiet_interrupts():
                portal.cancel(request)
                _wait_for_cancellation(request)
        raise
    error = request.error
    if error is not None:
        request.error = None
        try:
            raise error
        finally:
            del error
    return request.result


def _wait_for_cancellation(request: _Call) -> None:
    if not _wait_done(request, CANCEL_GRACE):
        LOGGER.error("A cancelled board call did not stop within %.1f s.", CANCEL_GRACE)


def _wait_done(request: _Call, timeout: float) -> bool:
    """Wait up to ``timeout`` seconds for ``request`` to finish; return whether it did.

    The loop also releases a caller's lock to let it run a signal handler (see
    :meth:`_LoopThread._let_callers_check_signals`), so a release alone does not mean
    done: only :attr:`_Call.state` does.
    """
    deadline = time.monotonic() + timeout
    while request.state != _DONE:
        remaining = deadline - time.monotonic()
        if remaining <= 0 or not request.done.acquire(timeout=remaining):
            return request.state == _DONE
    return True


async def _make_safe_and_close() -> None:
    await make_all_safe_uncancellably(SHUTDOWN_TIMEOUT)

    async def close(board: Board) -> None:
        with anyio.move_on_after(SHUTDOWN_TIMEOUT):
            try:
                await board.close()
            except Exception as exc:
                LOGGER.error("Could not close %s: %r", board, exc)

    async with anyio.create_task_group() as group:
        for board in list(Board.BOARDS):
            group.start_soon(close, board)


def shutdown() -> None:
    """Make every board safe, close every board's port, then stop the loop thread.

    Runs by itself when the program ends (an exit step of :mod:`j5aio.lifetime`); calling
    it earlier is allowed, after which the next blocking call starts a new loop thread.
    """
    global _portal
    with _lock:
        portal, _portal = _portal, None
    if portal is None or not portal.thread.is_alive():
        return
    current = portal._current
    if current is not None:
        portal.cancel(current)
    try:
        request = portal.submit(_make_safe_and_close())
        if not _wait_done(request, 3 * SHUTDOWN_TIMEOUT):
            LOGGER.error("Boards were not made safe within %.1f s.", 3 * SHUTDOWN_TIMEOUT)
        elif request.error is not None:
            LOGGER.error("Could not make the boards safe: %r", request.error)
    finally:
        portal.stop(SHUTDOWN_TIMEOUT)

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
* **Speed.** One persistent worker task per portal runs the calls one after another: a
  call costs a queue append, one ``call_soon_threadsafe`` (only when the worker is idle)
  and one lock hand-off. No task and no cancel scope are made per call: the worker's
  scope is replaced only after it has been used to cancel a call.

While the caller waits it blocks on a lock (waking once a second, :data:`LONG_WAIT_SLICE`):
an idle program costs next to no CPU. Signals still interrupt the wait at once, because
the portal thread (and every thread it starts: anyio's workers, USB links) blocks SIGINT,
SIGTERM and SIGHUP, so the kernel delivers them to the waiting main thread; one that
reaches a thread the program started itself is seen at the end of the slice. On Windows,
where a lock wait cannot be interrupted, the caller waits in slices of :data:`WAIT_SLICE`.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import signal
import sys
import threading
from collections import deque
from collections.abc import Awaitable, Callable, Coroutine
from typing import Any, Final, ParamSpec, TypeVar

import anyio

from j5aio import lifetime
from j5aio.boards.board import Board
from j5aio.safety import make_all_safe_uncancellably

__all__ = [
    "CANCEL_GRACE",
    "LONG_WAIT_SLICE",
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
#: Elsewhere, the same for a signal that reached another thread than the waiting one (a
#: thread the program started itself): it is seen within this many seconds.
LONG_WAIT_SLICE: Final = 1.0
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
    caller that sees "not done" knows it has not taken the lock yet.
    """

    __slots__ = ("coro", "done", "error", "result", "state")

    def __init__(self, coro: Coroutine[Any, Any, Any]) -> None:
        self.coro = coro
        self.done = threading.Lock()
        self.done.acquire()
        self.result: Any = None
        self.error: BaseException | None = None
        self.state = _QUEUED

    def finish(self) -> None:
        """Release the waiting caller (loop thread)."""
        self.state = _DONE
        self.done.release()

    def withdraw(self, reason: str) -> None:
        """Finish a call that never started, without running it (loop thread)."""
        self.coro.close()
        self.error = RuntimeError(reason)
        self.finish()


class _LoopThread:
    """The background thread, its event loop and its worker; created on first use."""

    def __init__(self) -> None:
        self.loop = asyncio.new_event_loop()
        self._queue: deque[_Call] = deque()
        self._current: _Call | None = None
        self._scope: anyio.CancelScope | None = None
        self._waiter: asyncio.Future[None] | None = None
        self._idle = False
        self._stopping = False
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
                request.finish()

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

    def submit(self, coro: Coroutine[Any, Any, T]) -> _Call:
        """Queue ``coro`` for the worker (from any thread but the loop's)."""
        request = _Call(coro)
        if self._stopping or self.loop.is_closed():
            coro.close()
            raise RuntimeError(
                "the j5aio sync portal has stopped (the program is exiting); "
                "no more board calls can be made",
            )
        self._queue.append(request)
        if self._idle:
            try:
                self.loop.call_soon_threadsafe(self._wake)
            except RuntimeError:  # the loop closed meanwhile (interpreter exit)
                with contextlib.suppress(ValueError):
                    self._queue.remove(request)
                coro.close()
                raise RuntimeError(
                    "the j5aio sync portal has stopped (the program is exiting); "
                    "no more board calls can be made",
                ) from None
        return request

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


_lock = threading.Lock()
_portal: _LoopThread | None = None


def _get_portal() -> _LoopThread:
    global _portal
    if _portal is not None:
        return _portal
    with _lock:
        if _portal is None:
            lifetime.install()
            lifetime.add_exit_step(shutdown)
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
    request = portal.submit(coro)
    return _wait(portal, request)  # type: ignore[no-any-return]


def _wait(portal: _LoopThread, request: _Call) -> Any:
    done = request.done
    try:
        if _INTERRUPTIBLE_WAIT:
            while not done.acquire(timeout=LONG_WAIT_SLICE):
                pass
        else:  # pragma: no cover - Windows
            while not done.acquire(timeout=WAIT_SLICE):
                pass
    except BaseException:
        if request.state != _DONE:  # not finished, so the lock is not ours: cancel, wait
            with lifetime.quiet_interrupts():
                portal.cancel(request)
                if not done.acquire(timeout=CANCEL_GRACE):
                    LOGGER.error(
                        "A cancelled board call did not stop within %.1f s.", CANCEL_GRACE
                    )
        raise
    error = request.error
    if error is not None:
        request.error = None
        try:
            raise error
        finally:
            del error
    return request.result


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
        if not request.done.acquire(timeout=3 * SHUTDOWN_TIMEOUT):
            LOGGER.error("Boards were not made safe within %.1f s.", 3 * SHUTDOWN_TIMEOUT)
        elif request.error is not None:
            LOGGER.error("Could not make the boards safe: %r", request.error)
    finally:
        portal.stop(SHUTDOWN_TIMEOUT)

"""The portal behind the sync facade: one event-loop thread per process.

Every blocking call of the facade hands a coroutine to :func:`call`, which runs it in a
background thread that owns an asyncio event loop (:mod:`j5aio.sync._loop_thread`), and
waits for its result. The parts, one job each:

* :mod:`j5aio.sync._calls`: one call, its state and the lock its caller waits on;
* :mod:`j5aio.sync._selectors`: the loop's selector, with hooks around each wait and a
  cheaper sleep while it watches no file;
* :mod:`j5aio.sync._loop_thread`: the thread, its loop and the worker that runs calls;
* :mod:`j5aio.sync._signals`: signals reach a main thread that waits on a lock;
* this module: :func:`call` (submit, wait, cancel on interruption) and :func:`shutdown`.

Three things matter more than anything else here:

* **Cancellation.** If the waiting thread is interrupted (Ctrl-C, SIGTERM turned into
  ``SystemExit``, any ``BaseException``), the coroutine is cancelled through an anyio
  cancel scope (so shielded transport exchanges stay whole) and the caller waits briefly
  for the cancellation to land before re-raising, so that a motor command cannot complete
  after the program has moved on. A call withdrawn before it started never runs. An
  interrupt that lands just after the call finished finds it finished and does not wait.
* **Exit.** The loop thread is a daemon. :func:`shutdown` is an exit step of the safety
  net (:mod:`j5aio.lifetime`): when the program ends, every board is made safe and its
  port closed through the loop, the loop stops, and the net then catches any board that
  was left. A beginner who never closes anything still gets a prompt exit.
* **Speed and rest.** A call costs two thread wake-ups (see
  :mod:`j5aio.sync._loop_thread`). While the caller waits it blocks on a lock with no
  time limit: an idle program (a beginner's ``wait_until_pressed``) costs no CPU at all,
  in the caller's thread or in the loop's, and signals still interrupt the wait at once
  (:mod:`j5aio.sync._signals`). On Windows, where a lock wait cannot be interrupted, the
  caller waits in slices of :data:`WAIT_SLICE`.
"""

from __future__ import annotations

import asyncio
import logging
import threading
import time
from collections.abc import Awaitable, Callable
from typing import Any, Final, ParamSpec, TypeVar

import anyio

from j5aio import lifetime
from j5aio.boards.board import Board
from j5aio.safety import make_all_safe_uncancellably
from j5aio.sync._calls import DONE, Call, new_done_lock
from j5aio.sync._loop_thread import LoopThread
from j5aio.sync._signals import INTERRUPTIBLE_WAIT, start_signal_watch

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

_lock = threading.Lock()
_portal: LoopThread | None = None


def _wake_waiting_callers() -> None:
    """Have the callers waiting on the portal check for signals (the signal watcher)."""
    portal = _portal
    if portal is not None:
        portal.wake_callers()


def _get_portal() -> LoopThread:
    global _portal
    if _portal is not None:
        return _portal
    with _lock:
        if _portal is None:
            lifetime.install()
            lifetime.add_exit_step(shutdown)
            start_signal_watch(_wake_waiting_callers)
            _portal = LoopThread()
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
        done = _per_thread.done = new_done_lock()
    return _wait(portal, portal.submit(coro, done))  # type: ignore[no-any-return]


#: Per calling thread, the held lock its calls wait on (one lock for all its calls).
_per_thread = threading.local()


def _wait(portal: LoopThread, request: Call) -> Any:
    done = request.done
    try:
        if INTERRUPTIBLE_WAIT:
            # A release before the call is done wakes us to run a signal's handler.
            while not done.acquire() or request.state != DONE:
                pass
        else:  # pragma: no cover - Windows
            while not done.acquire(timeout=WAIT_SLICE) or request.state != DONE:
                pass
    except BaseException:
        if getattr(_per_thread, "done", None) is done:
            # Whether the loop has released it yet or will later, this lock is spent.
            _per_thread.done = new_done_lock()
        if request.state != DONE:  # not finished, so the lock is not ours: cancel, wait
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


def _wait_for_cancellation(request: Call) -> None:
    if not _wait_done(request, CANCEL_GRACE):
        LOGGER.error("A cancelled board call did not stop within %.1f s.", CANCEL_GRACE)


def _wait_done(request: Call, timeout: float) -> bool:
    """Wait up to ``timeout`` seconds for ``request`` to finish; return whether it did.

    The loop also releases a caller's lock to let it run a signal handler (see
    :meth:`LoopThread.wake_callers`), so a release alone does not mean done: only
    :attr:`Call.state` does.
    """
    deadline = time.monotonic() + timeout
    while request.state != DONE:
        remaining = deadline - time.monotonic()
        if remaining <= 0 or not request.done.acquire(timeout=remaining):
            return request.state == DONE
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
    current = portal.current
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

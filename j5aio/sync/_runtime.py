"""The portal behind the sync facade: the event loop every blocking call runs in.

Every blocking call of the facade hands a coroutine to :func:`call`, which runs it in the
facade's one event loop and returns its result. Where it can (POSIX), the calling thread
runs the loop itself (:mod:`j5aio.sync._driven`): no other thread is woken for a call, and
a keeper thread runs the loop only while the program is away from calls. Elsewhere (or
when :data:`CALLER_DRIVES` is turned off) a loop thread runs every call for its callers
(:mod:`j5aio.sync._loop_thread`). The parts, one job each:

* :mod:`j5aio.sync._calls`: one call, its state and the lock its caller waits on;
* :mod:`j5aio.sync._driven`: the loop driven by its callers, its worker and its keeper;
* :mod:`j5aio.sync._deferral`: signals for a main thread that is running the loop;
* :mod:`j5aio.sync._selectors`: the loop thread's selector, with hooks around each wait
  and a cheaper sleep while it watches no file;
* :mod:`j5aio.sync._loop_thread`: the hand-off portal's thread, its loop and its worker;
* :mod:`j5aio.sync._signals`: signals reach a main thread that waits on a lock;
* this module: :func:`call` (run, or submit and wait, cancel on interruption) and
  :func:`shutdown`.

Three things matter more than anything else here:

* **Cancellation.** If the caller is interrupted (Ctrl-C, SIGTERM turned into
  ``SystemExit``, any ``BaseException``), the coroutine is cancelled through an anyio
  cancel scope (so shielded transport exchanges stay whole) and the caller waits briefly
  for the cancellation to land before re-raising (at most :data:`CANCEL_GRACE`), so that
  a motor command cannot complete after the program has moved on. A call withdrawn before
  it started never runs. An interrupt that lands just after the call finished finds it
  finished and does not wait. A main thread that runs the loop gets its signals at the
  call's boundary, never inside the loop (:mod:`j5aio.sync._deferral`).
* **Exit.** :func:`shutdown` is an exit step of the safety net (:mod:`j5aio.safety.hooks`):
  when the program ends, every board is made safe and its port closed through the loop,
  whoever was running it, the loop stops, and the net then catches any board that was
  left. A beginner who never closes anything still gets a prompt exit.
* **Speed and rest.** A call run by its caller costs no thread wake-up at all. While a
  call waits (a beginner's ``wait_until_pressed``) its thread sleeps in the loop's
  selector, or on a lock with no time limit when another thread runs the loop: an idle
  program costs no CPU, and signals still interrupt the wait at once
  (:mod:`j5aio.sync._signals`). On Windows, where a lock wait cannot be interrupted, the
  caller waits in slices of :data:`WAIT_SLICE`.
"""

from __future__ import annotations

import asyncio
import logging
import threading
import time
from collections.abc import Awaitable, Callable
from typing import TYPE_CHECKING, Any, Final, ParamSpec, TypeVar

import anyio

from j5aio.boards.board import Board
from j5aio.safety import hooks as safety_hooks
from j5aio.safety import make_all_safe_uncancellably
from j5aio.sync._calls import CANCEL_GRACE, DONE, Call, new_done_lock
from j5aio.sync._driven import NESTED_CALL, DrivenLoop
from j5aio.sync._signals import INTERRUPTIBLE_WAIT, start_signal_watch

if TYPE_CHECKING:  # (imported only where the callers cannot drive the loop)
    from j5aio.sync._loop_thread import LoopThread

__all__ = [
    "CALLER_DRIVES",
    "CANCEL_GRACE",
    "SHUTDOWN_TIMEOUT",
    "WAIT_SLICE",
    "call",
    "get_loop",
    "shutdown",
]


def _logger() -> logging.Logger:
    """The runtime's logger, looked up when something goes wrong: a start makes none."""
    return logging.getLogger(__name__)


P = ParamSpec("P")
T = TypeVar("T")

#: Whether the calling thread runs the loop itself (:mod:`j5aio.sync._driven`): where a
#: blocked main thread is interrupted by signals (POSIX). Otherwise a loop thread runs it.
CALLER_DRIVES: Final = INTERRUPTIBLE_WAIT
#: On Windows, how long one wait for a result lasts before checking for Ctrl-C again.
WAIT_SLICE: Final = 0.05
#: How long making boards safe in order, and closing them, may each take at exit.
SHUTDOWN_TIMEOUT: Final = 0.5

_lock = threading.Lock()
_portal: DrivenLoop | LoopThread | None = None


def _wake_waiting_callers() -> None:
    """Have the callers waiting on the portal check for signals (the signal watcher)."""
    portal = _portal
    if portal is not None:
        portal.wake_callers()


def _get_portal() -> DrivenLoop | LoopThread:
    global _portal
    if _portal is not None:
        return _portal
    with _lock:
        if _portal is None:
            safety_hooks.install()
            safety_hooks.add_exit_step(shutdown)
            if CALLER_DRIVES:  # its loop hears of signals itself: no watcher thread
                _portal = DrivenLoop(on_signal=_wake_waiting_callers)
            else:
                from j5aio.sync._loop_thread import LoopThread

                start_signal_watch(_wake_waiting_callers)
                _portal = LoopThread()
        return _portal


def get_loop() -> asyncio.AbstractEventLoop:
    """Return the portal's event loop, making it (and starting its thread) if needed."""
    return _get_portal().loop


def call(fn: Callable[P, Awaitable[T]], /, *args: P.args, **kwargs: P.kwargs) -> T:
    """Run ``fn(*args, **kwargs)`` in the portal's loop and return its result.

    If the calling thread is interrupted meanwhile, the coroutine is cancelled and the
    interruption is re-raised once the cancellation has landed (or after
    ``CANCEL_GRACE`` seconds).

    :raises RuntimeError: called from async code running in the portal's own loop (use
        ``await`` there), or the program is exiting and the portal has stopped.
    """
    portal = _portal if _portal is not None else _get_portal()
    if type(portal) is DrivenLoop:
        coro = fn(*args, **kwargs)
        if not asyncio.iscoroutine(coro):
            raise TypeError(f"{fn!r} did not return a coroutine")
        return portal.run(coro, _wait)  # type: ignore[no-any-return]
    assert not isinstance(portal, DrivenLoop)
    if threading.get_ident() == portal.thread.ident:
        raise RuntimeError(NESTED_CALL)
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


def _wait(portal: DrivenLoop | LoopThread, request: Call) -> Any:
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
            with safety_hooks.quiet_interrupts():
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
        _logger().error("A cancelled board call did not stop within %.1f s.", CANCEL_GRACE)


def _wait_done(request: Call, timeout: float) -> bool:
    """Wait up to ``timeout`` seconds for ``request`` to finish; return whether it did.

    The loop also releases a caller's lock to let it run a signal handler (see
    :meth:`~j5aio.sync._loop_thread.LoopThread.wake_callers`), so a release alone does
    not mean done: only :attr:`Call.state` does.
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
                _logger().error("Could not close %s: %r", board, exc)

    async with anyio.create_task_group() as group:
        for board in list(Board.BOARDS):
            group.start_soon(close, board)


def shutdown() -> None:
    """Make every board safe, close every board's port, then stop the loop (and its thread).

    Runs by itself when the program ends (an exit step of :mod:`j5aio.safety.hooks`); calling
    it earlier is allowed, after which the next blocking call makes a new loop.
    """
    global _portal
    with _lock:
        portal, _portal = _portal, None
    if portal is None:
        return
    if isinstance(portal, DrivenLoop):
        _close_driven(portal)
        return
    if not portal.thread.is_alive():
        return
    current = portal.current
    if current is not None:
        portal.cancel(current)
    try:
        request = portal.submit(_make_safe_and_close())
        if not _wait_done(request, 3 * SHUTDOWN_TIMEOUT):
            _logger().error("Boards were not made safe within %.1f s.", 3 * SHUTDOWN_TIMEOUT)
        elif request.error is not None:
            _logger().error("Could not make the boards safe: %r", request.error)
    finally:
        portal.stop(SHUTDOWN_TIMEOUT)


def _close_driven(portal: DrivenLoop) -> None:
    """Shut the caller-driven loop down, whoever is running it now."""
    try:
        error = portal.close(_make_safe_and_close(), 3 * SHUTDOWN_TIMEOUT)
    except TimeoutError:
        _logger().error("Boards were not made safe within %.1f s.", 3 * SHUTDOWN_TIMEOUT)
    else:
        if error is not None:
            _logger().error("Could not make the boards safe: %r", error)

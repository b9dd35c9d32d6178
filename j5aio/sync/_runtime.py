"""The portal behind the sync facade: one event-loop thread per process.

Every blocking call of the facade hands a coroutine to :func:`call`, which runs it in a
background thread that owns an asyncio event loop, and waits for its result.

Three things matter more than anything else here:

* **Cancellation.** If the waiting thread is interrupted (Ctrl-C, SIGTERM turned into
  ``SystemExit``, any ``BaseException``), the coroutine is cancelled through an anyio
  cancel scope (so shielded transport exchanges stay whole) and the caller waits briefly
  for the cancellation to land before re-raising, so that a motor command cannot complete
  after the program has moved on.
* **Exit.** The loop thread is a daemon and is stopped from a hook that runs before the
  interpreter joins its threads: every board is made safe, every board's port is closed,
  then the loop stops. A beginner who never closes anything still gets a prompt exit.
* **Speed.** A call costs one ``call_soon_threadsafe`` and one lock hand-off; there is no
  ``concurrent.futures`` machinery in the way.
"""

from __future__ import annotations

import asyncio
import atexit
import contextlib
import logging
import signal
import sys
import threading
from collections.abc import Awaitable, Callable, Coroutine
from types import FrameType
from typing import Any, Final, ParamSpec, TypeVar

import anyio

from j5aio.boards.board import Board
from j5aio.safety import make_all_safe_uncancellably

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

#: How long one wait for a result lasts before checking for Ctrl-C again, in seconds.
WAIT_SLICE: Final = 0.05
#: How long an interrupted caller waits for its coroutine's cancellation to land.
CANCEL_GRACE: Final = 2.0
#: How long making boards safe and closing them may take when the program exits.
SHUTDOWN_TIMEOUT: Final = 5.0


class _Call:
    """One coroutine handed to the loop thread, and the lock its caller waits on."""

    __slots__ = ("cancel_requested", "coro", "done", "error", "result", "scope")

    def __init__(self, coro: Coroutine[Any, Any, Any]) -> None:
        self.coro = coro
        self.done = threading.Lock()
        self.done.acquire()
        self.result: Any = None
        self.error: BaseException | None = None
        self.scope: anyio.CancelScope | None = None
        self.cancel_requested = False

    async def run(self) -> None:
        """Run the coroutine in the loop thread, then release the waiting caller."""
        try:
            if self.cancel_requested:
                self.coro.close()
                return
            with anyio.CancelScope() as scope:
                self.scope = scope
                self.result = await self.coro
            if scope.cancelled_caught:
                self.error = RuntimeError(
                    "the board call was cancelled: the j5aio sync portal is stopping",
                )
        except BaseException as exc:
            self.error = exc
        finally:
            self.done.release()

    def cancel(self) -> None:
        """Cancel the coroutine (runs in the loop thread)."""
        self.cancel_requested = True
        if self.scope is not None:
            self.scope.cancel()


class _LoopThread:
    """The background thread and its event loop; created on first use."""

    def __init__(self) -> None:
        self.loop = asyncio.new_event_loop()
        self._stop: asyncio.Event | None = None
        self.pending: dict[_Call, asyncio.Task[None] | None] = {}
        ready = threading.Event()
        self.thread = threading.Thread(
            target=self._run, args=(ready,), name="j5aio sync portal", daemon=True,
        )
        self.thread.start()
        ready.wait()

    def _run(self, ready: threading.Event) -> None:
        asyncio.set_event_loop(self.loop)
        try:
            self.loop.run_until_complete(self._main(ready))
            self.loop.run_until_complete(self.loop.shutdown_asyncgens())
        finally:
            self.loop.close()

    async def _main(self, ready: threading.Event) -> None:
        # This task is the loop's root task: anyio ties its worker threads to it, so they
        # stop when it returns.
        self._stop = asyncio.Event()
        ready.set()
        await self._stop.wait()
        for pending in list(self.pending):
            pending.cancel()
        tasks = [task for task in self.pending.values() if task is not None]
        if tasks:
            await asyncio.wait(tasks, timeout=CANCEL_GRACE)

    def submit(self, coro: Coroutine[Any, Any, T]) -> _Call:
        request = _Call(coro)
        self.pending[request] = None
        try:
            self.loop.call_soon_threadsafe(self._start, request)
        except RuntimeError:  # the loop has stopped (interpreter exit)
            self.pending.pop(request, None)
            coro.close()
            raise RuntimeError(
                "the j5aio sync portal has stopped (the program is exiting); "
                "no more board calls can be made",
            ) from None
        return request

    def _start(self, request: _Call) -> None:
        task = self.loop.create_task(request.run())
        self.pending[request] = task
        task.add_done_callback(lambda _task: self.pending.pop(request, None))

    def stop(self, timeout: float) -> None:
        """Stop the loop (from any thread other than the loop's) and join the thread."""
        if self._stop is not None and self.thread.is_alive():
            with contextlib.suppress(RuntimeError):
                self.loop.call_soon_threadsafe(self._stop.set)
            self.thread.join(timeout)


_lock = threading.Lock()
_portal: _LoopThread | None = None


def _get_portal() -> _LoopThread:
    global _portal
    if _portal is not None:
        return _portal
    with _lock:
        if _portal is None:
            _portal = _LoopThread()
            _register_exit_hook()
            _install_signal_handlers()
        return _portal


def get_loop() -> asyncio.AbstractEventLoop:
    """Return the portal's event loop, starting its thread if needed."""
    return _get_portal().loop


def call(fn: Callable[P, Awaitable[T]], /, *args: P.args, **kwargs: P.kwargs) -> T:
    """Run ``fn(*args, **kwargs)`` in the portal's loop and return its result.

    If the calling thread is interrupted while waiting, the coroutine is cancelled and the
    interruption is re-raised once the cancellation has landed (or after
    :data:`CANCEL_GRACE` seconds).

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
        if not done.acquire(timeout=WAIT_SLICE):
            while not done.acquire(timeout=WAIT_SLICE):
                pass
    except BaseException:
        with contextlib.suppress(RuntimeError):
            portal.loop.call_soon_threadsafe(request.cancel)
        if not done.acquire(timeout=CANCEL_GRACE):
            LOGGER.error("A cancelled board call did not stop within %.1f s.", CANCEL_GRACE)
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

    Runs by itself when the program exits; calling it earlier is allowed, after which
    the next blocking call starts a new loop thread.
    """
    global _portal
    with _lock:
        portal, _portal = _portal, None
    if portal is None or not portal.thread.is_alive():
        return
    for pending in list(portal.pending):
        with contextlib.suppress(RuntimeError):
            portal.loop.call_soon_threadsafe(pending.cancel)
    try:
        request = portal.submit(_make_safe_and_close())
        if not request.done.acquire(timeout=2 * SHUTDOWN_TIMEOUT):
            LOGGER.error("Boards were not made safe within %.1f s.", 2 * SHUTDOWN_TIMEOUT)
        elif request.error is not None:
            LOGGER.error("Could not make the boards safe: %r", request.error)
    finally:
        portal.stop(SHUTDOWN_TIMEOUT)


_hook_registered = False


def _register_exit_hook() -> None:
    # threading's own exit hooks run before the interpreter joins non-daemon threads
    # (anyio's worker threads are non-daemon and only stop when our loop does), and
    # before concurrent.futures refuses new work, so closing a port still works there.
    global _hook_registered
    if _hook_registered:
        return
    _hook_registered = True
    register = getattr(threading, "_register_atexit", None)
    if register is not None:
        try:
            register(shutdown)
        except RuntimeError:  # pragma: no cover - already shutting down
            atexit.register(shutdown)
    else:  # pragma: no cover - every CPython we support has it
        atexit.register(shutdown)


def _on_terminate(signum: int, frame: FrameType | None) -> None:
    LOGGER.error("Terminated by %s: making every board safe.", signal.Signals(signum).name)
    raise SystemExit(128 + signum)


def _install_signal_handlers() -> None:
    """Turn SIGTERM (and SIGHUP) into ``SystemExit`` so the exit hook makes boards safe."""
    if threading.current_thread() is not threading.main_thread():
        return
    names = ["SIGTERM"] if sys.platform == "win32" else ["SIGTERM", "SIGHUP"]
    for name in names:
        signum = getattr(signal, name)
        with contextlib.suppress(ValueError, OSError):
            if signal.getsignal(signum) is signal.SIG_DFL:
                signal.signal(signum, _on_terminate)

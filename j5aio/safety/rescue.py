"""The sync rescue: every open board made safe now, through its own link, from any thread.

However a program ends (the end of its event loop, the end of the interpreter, a signal,
an unhandled exception; :mod:`j5aio.safety.hooks` says when), a board that was opened
and not closed is made safe by :func:`make_all_safe_now`, which calls each open board's
:meth:`~j5aio.backends.backend.Backend.make_safe_now` (the synchronous safe state every
backend provides) within :data:`NET_BUDGET` seconds in all. It works from any thread: a
board whose event loop runs in another thread is made safe by a callback in that loop
(so its bytes never interleave with a command being written there), and directly if that
loop does not answer in time. Each board it had to rescue gets one log line, so that a
team knows their program relied on it; boards settled in order first
(:mod:`j5aio.safety.orderly`) are made safe again without a line.
"""

from __future__ import annotations

import asyncio
import logging
import sys
import threading
import time
from typing import TYPE_CHECKING, Final

from j5aio.safety import registry

if TYPE_CHECKING:
    from j5aio.boards.board import Board

__all__ = ["NET_BUDGET", "PER_BOARD_TIMEOUT", "failures", "make_all_safe_now", "watch"]

LOGGER = logging.getLogger("j5aio.lifetime")  # the name teams' log settings know

#: The most seconds the net may spend on all boards together.
NET_BUDGET: Final = 1.0
#: The most seconds one board may take to be made safe (within the budget).
PER_BOARD_TIMEOUT: Final = 0.5

#: id(loop) -> its watcher task (held here: asyncio keeps only weak references to tasks).
_watchers: dict[int, asyncio.Task[None]] = {}
#: How many boards the net could not make safe (for the line printed on Ctrl-C).
_failures = 0


def failures() -> int:
    """How many boards the rescue could not make safe so far."""
    return _failures


def make_all_safe_now(
    reason: str,
    *,
    close: bool = False,
    loop: asyncio.AbstractEventLoop | None = None,
    budget: float = NET_BUDGET,
    loop_wait: float | None = None,
) -> list[Board]:
    """Make every open board safe now, synchronously, through its own link.

    Callable from any thread, also while the boards' event loops run (a game-over
    watchdog can call it): boards whose loop runs in another thread are made safe by a
    callback in that loop, or directly if the loop does not run it within the budget.
    A board that fails is logged and skipped.

    :param reason: why, for the log lines ("the program exited", ...).
    :param close: also close each board's port and forget the board (at the end of its
        loop or of the program); otherwise the boards stay usable.
    :param loop: only the boards opened in this loop.
    :param budget: the most seconds to spend, for all boards together.
    :param loop_wait: the most seconds to wait for a loop running in another thread to
        start the work before doing it from here; half the budget if ``None``. A caller
        with a deadline of its own (the match timer's game over) passes a short wait.
    :returns: the boards that had to be rescued (something was sent to them and they had
        not been made safe in order before).
    """
    deadline = time.monotonic() + budget
    with registry._lock:
        chosen = [(b, lp) for b, lp in registry._open.items() if loop is None or lp is loop]
    by_loop: dict[asyncio.AbstractEventLoop | None, list[Board]] = {}
    for board, board_loop in chosen:
        by_loop.setdefault(board_loop, []).append(board)
    rescued: list[Board] = []
    for board_loop, boards in by_loop.items():
        if board_loop is not None and _runs_elsewhere(board_loop):
            rescued += _in_loop(board_loop, boards, reason, close, deadline, loop_wait)
        else:
            rescued += _make_safe(boards, reason, close, deadline)
    return rescued


def _runs_elsewhere(loop: asyncio.AbstractEventLoop) -> bool:
    """Whether ``loop`` is running in a thread other than this one."""
    if loop.is_closed() or not loop.is_running():
        return False
    try:
        current = asyncio.get_running_loop()
    except RuntimeError:
        current = None
    return current is not loop


def _in_loop(
    loop: asyncio.AbstractEventLoop,
    boards: list[Board],
    reason: str,
    close: bool,
    deadline: float,
    loop_wait: float | None = None,
) -> list[Board]:
    done = threading.Event()
    result: list[Board] = []
    claimed = threading.Lock()

    def run() -> None:
        if claimed.acquire(blocking=False):
            try:
                result.extend(_make_safe(boards, reason, close, deadline))
            finally:
                done.set()

    try:
        loop.call_soon_threadsafe(run)
    except RuntimeError:  # the loop closed meanwhile
        pass
    else:
        left = max(deadline - time.monotonic(), 0)
        if done.wait(left / 2 if loop_wait is None else min(loop_wait, left)):
            return result
    if claimed.acquire(blocking=False):  # the loop did not answer: do it from here
        LOGGER.debug("The event loop of %s did not answer; making them safe directly", boards)
        return _make_safe(boards, reason, close, deadline)
    done.wait(max(deadline - time.monotonic(), 0))  # the loop started it: let it finish
    return result


def _make_safe(boards: list[Board], reason: str, close: bool, deadline: float) -> list[Board]:
    global _failures
    rescued = []
    # The boards that power the others (MAKE_SAFE_LAST) after them.
    for board in sorted(boards, key=lambda board: board.MAKE_SAFE_LAST):
        left = deadline - time.monotonic()
        with registry._lock:
            if board not in registry._open:
                continue  # closed meanwhile
            settled = board in registry._settled
        if left <= 0:
            LOGGER.error("No time left to make %s safe (%s).", board, reason)
            _failures += 1
            continue
        make_safe_now = getattr(board.backend, "make_safe_now", None)
        if make_safe_now is None:
            # Not a j5aio Backend (a test's stand-in, or a board whose construction failed
            # on its backend): it drives nothing that could be left running.
            LOGGER.debug("%s has no safe state to send (its backend is not a Backend).", board)
            continue
        try:
            sent = make_safe_now(min(left, PER_BOARD_TIMEOUT))
        except Exception as exc:
            LOGGER.error("Could not make %s safe when %s: %s", board, reason, exc)
            _failures += 1
            sent = False
        if sent and not settled:
            rescued.append(board)
            LOGGER.warning(
                "%s was made safe by j5aio's safety net when %s (it was never closed).",
                board,
                reason,
            )
        if close:
            board.close_now()
    return rescued


# -- when: the end of a loop ---------------------------------------------------------------


def watch(loop: asyncio.AbstractEventLoop) -> None:
    """Make the boards opened in ``loop`` safe when it finishes (once per loop)."""
    with registry._lock:
        if id(loop) in _watchers:
            return
        _watchers[id(loop)] = loop.create_task(_watch_loop(loop), name="j5aio safety net")


async def _watch_loop(loop: asyncio.AbstractEventLoop) -> None:
    """Wait for the end of the loop (its runner cancels this task), then rescue its boards.

    A loop that is never ended (a program stopped while it ran) leaves this task to be
    closed by the garbage collector as the interpreter shuts down, after the exit hook
    has made every board safe: then there is nothing left to do, and the module's globals
    may already be gone, so what the rescue needs is held from the start.
    """
    watchers, lock, rescue, finalizing = _watchers, registry._lock, make_all_safe_now, (
        sys.is_finalizing
    )
    try:
        await loop.create_future()
    finally:
        if not finalizing():
            with lock:
                watchers.pop(id(loop), None)
            rescue("its event loop finished", close=True, loop=loop)


# Every board opened while a loop runs is made safe when that loop ends: the registry
# tells this module of the loop (it does not import the rescue, which reads it).
registry.on_board_in_loop(watch)

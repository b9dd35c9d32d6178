"""The safety net: every board j5aio opened is made safe when the program ends.

However a program is written (a robot, the sync facade, or a quick ``anyio.run`` script
with no robot at all) and however it ends, a board that was opened and not closed is made
safe through its own link:

* when the event loop it was opened in finishes (``asyncio.run`` / ``anyio.run`` cancel
  their remaining tasks at the end; a watcher task per loop notices);
* when the interpreter exits (a hook that runs before Python joins its threads);
* on SIGTERM and SIGHUP (turned into ``SystemExit(128 + signal)``, or handed to a
  running :class:`~j5aio.robot.BaseRobot`, which stops in order and exits the same way);
* when an unhandled exception ends the program (from ``sys.excepthook``, before the
  traceback is printed; Ctrl-C prints one short line instead of a traceback unless debug
  logging is on).

How: :func:`make_all_safe_now` calls each open board's
:meth:`~j5aio.backends.backend.Backend.make_safe_now`, the synchronous safe state that
every backend provides (see there for the contract), within :data:`NET_BUDGET` seconds in
all. It works from any thread: a board whose event loop is running in another thread is
made safe by a callback in that loop (so its bytes never interleave with a command being
written there), and directly if that loop does not answer in time. Each board it had to
rescue gets one log line, so that a team knows their program relied on it; boards that
were made safe in order first (:meth:`~j5aio.boards.board.Board.make_all_safe`, as a
robot and the sync facade do on the way out) are made safe again without a line.

Orderly shutdowns (the sync facade's) register with :func:`add_exit_step`: they run first,
then the net catches whatever they left. A robot asks for SIGTERM with
:func:`on_terminate`. So there is one exit hook, one set of signal handlers and one
excepthook for the whole library.
"""

from __future__ import annotations

import asyncio
import atexit
import contextlib
import logging
import signal
import sys
import threading
import time
from collections.abc import Callable, Iterator
from types import FrameType, TracebackType
from typing import TYPE_CHECKING, Any, Final

from j5aio.errors import GameOverError

if TYPE_CHECKING:
    from j5aio.boards.board import Board

__all__ = [
    "GAME_OVER_WAIT",
    "NET_BUDGET",
    "PER_BOARD_TIMEOUT",
    "add_exit_step",
    "begin_game_over",
    "end_game_over",
    "game_over_begun",
    "install",
    "make_all_safe_now",
    "mark_settled",
    "on_terminate",
    "open_boards",
    "quiet_interrupts",
    "track",
    "untrack",
    "wait_for_game_over",
]

LOGGER = logging.getLogger(__name__)

#: The most seconds the net may spend on all boards together.
NET_BUDGET: Final = 1.0
#: The most seconds one board may take to be made safe (within the budget).
PER_BOARD_TIMEOUT: Final = 0.5

_STOPPING_SIGNALS: Final = tuple(
    getattr(signal, name) for name in ("SIGINT", "SIGTERM", "SIGHUP") if hasattr(signal, name)
)

_lock = threading.RLock()
#: Every board opened and not closed -> the event loop it was opened in (None: none ran).
_open: dict[Board, asyncio.AbstractEventLoop | None] = {}
#: Boards made safe in order since they were opened (no log line if the net sends again).
_settled: set[Board] = set()
#: id(loop) -> its watcher task (held here: asyncio keeps only weak references to tasks).
_watchers: dict[int, asyncio.Task[None]] = {}
_exit_steps: list[Callable[[], None]] = []
_terminate_handlers: list[tuple[asyncio.AbstractEventLoop, Callable[[int], None]]] = []
_installed = False
_signals_installed = False
_finished = False
#: How many boards the net could not make safe (for the line printed on Ctrl-C).
_failures = 0
#: Whether a terminating signal has been asked to stop a running loop.
_terminating = False
#: Set when game over begins: from then on no board may be opened.
_game_over = threading.Event()
#: Set when game over has finished (the process is ending).
_game_over_done = threading.Event()
#: The most seconds a program that ends during game over waits for game over to end it.
GAME_OVER_WAIT: Final = 5.0


# -- which boards are open ---------------------------------------------------------------


def track(board: Board) -> None:
    """Remember ``board`` as opened (boards call this when they are made).

    The event loop running now, if any, is the board's: when it finishes, the board is
    made safe and closed.

    :raises ~j5aio.errors.GameOverError: the match is over (the board's port is closed
        at once: after game over nothing may drive a board again).
    """
    try:
        loop: asyncio.AbstractEventLoop | None = asyncio.get_running_loop()
    except RuntimeError:
        loop = None
    with _lock:
        sealed = _game_over.is_set()
        if not sealed:
            _open[board] = loop
            _settled.discard(board)
    if sealed:
        close_now = getattr(board.backend, "close_now", None)
        if close_now is not None:
            with contextlib.suppress(Exception):
                close_now()
        raise GameOverError(
            f"the match is over: {board} cannot be opened after game over (the program "
            "is ending with every board safe)"
        )
    install()
    if loop is not None:
        _watch(loop)


def untrack(board: Board) -> None:
    """Forget ``board``: it has been closed cleanly."""
    with _lock:
        _open.pop(board, None)
        _settled.discard(board)


def mark_settled(board: Board) -> None:
    """Note that ``board`` was made safe in order (the net then sends again silently)."""
    with _lock:
        if board in _open:
            _settled.add(board)


def open_boards() -> list[Board]:
    """Every board opened and not yet closed."""
    with _lock:
        return list(_open)


# -- game over ---------------------------------------------------------------------------


def begin_game_over() -> None:
    """The match has ended: from now on opening a board raises, and the program's end waits.

    The match timer calls this before it makes the boards safe, so that a program cannot
    open fresh links and drive again before the process ends. A program that ends
    meanwhile (an unhandled exception, the end of its code) waits for game over to end
    the process, so that it ends with "Game over" and status 0, not a traceback.
    """
    with _lock:
        _game_over.set()


def game_over_begun() -> bool:
    """Whether the match has ended (:func:`begin_game_over` was called)."""
    return _game_over.is_set()


def end_game_over() -> None:
    """Game over has finished (its process-ending call returned: only in tests)."""
    _game_over_done.set()


def wait_for_game_over(timeout: float = GAME_OVER_WAIT) -> bool:
    """If game over has begun, wait (at most ``timeout`` s) for it to end the process.

    :returns: whether game over had begun.
    """
    if not _game_over.is_set():
        return False
    _game_over_done.wait(timeout)
    return True


# -- the net -----------------------------------------------------------------------------


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
    with _lock:
        chosen = [(b, lp) for b, lp in _open.items() if loop is None or lp is loop]
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
        with _lock:
            if board not in _open:
                continue  # closed meanwhile
            settled = board in _settled
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


def _watch(loop: asyncio.AbstractEventLoop) -> None:
    with _lock:
        if id(loop) in _watchers:
            return
        _watchers[id(loop)] = loop.create_task(_watch_loop(loop), name="j5aio safety net")


async def _watch_loop(loop: asyncio.AbstractEventLoop) -> None:
    """Wait for the end of the loop (its runner cancels this task), then rescue its boards."""
    try:
        await loop.create_future()
    finally:
        with _lock:
            _watchers.pop(id(loop), None)
        make_all_safe_now("its event loop finished", close=True, loop=loop)


# -- when: the end of the program ----------------------------------------------------------


def add_exit_step(step: Callable[[], None]) -> None:
    """Run ``step`` when the program ends, before the net (an orderly shutdown)."""
    with _lock:
        if step not in _exit_steps:
            _exit_steps.append(step)


def _finish(reason: str) -> None:
    """Run the exit steps, then the net over every board still open; once."""
    global _finished
    # The match timer is ending the match: it makes the boards safe, logs "Game over"
    # and ends the process with status 0; the program's own end must not pre-empt it.
    wait_for_game_over()
    with _lock:
        if _finished:
            return
        _finished = True
        steps = list(_exit_steps)
    with quiet_interrupts():
        for step in steps:
            try:
                step()
            except Exception as exc:
                LOGGER.error("Stopping: %r failed: %s", step, exc)
        make_all_safe_now(reason, close=True)


def _at_exit() -> None:
    _finish("the program exited")


def _excepthook(
    kind: type[BaseException], value: BaseException, traceback: TracebackType | None
) -> None:
    interactive = hasattr(sys, "ps1") or sys.flags.interactive
    if wait_for_game_over():
        # The program ended because the match did (its boards were closed under it): the
        # match timer ends the process with "Game over" and status 0, not this traceback.
        LOGGER.debug("The program stopped at game over on %s", kind.__name__)
        return
    if not interactive:
        if issubclass(kind, KeyboardInterrupt):
            _finish("the program was stopped with Ctrl-C")
        else:
            _finish(f"the program stopped on an unhandled {kind.__name__}")
    if (
        issubclass(kind, KeyboardInterrupt)
        and not interactive
        and not logging.getLogger("j5aio").isEnabledFor(logging.DEBUG)
    ):
        if _failures:
            message = "Stopped (Ctrl-C); some boards could not be made safe (see above)."
        else:
            message = "Stopped (Ctrl-C); every board was made safe."
        print(message, file=sys.stderr, flush=True)
        # The program is ending: a further Ctrl-C would only tear the interpreter's own
        # exit hooks (with a traceback), so it is ignored from now on.
        if threading.current_thread() is threading.main_thread():
            with contextlib.suppress(ValueError, OSError):
                signal.signal(signal.SIGINT, _ignore_interrupt)
        return
    _previous_excepthook(kind, value, traceback)


_previous_excepthook = sys.excepthook


@contextlib.contextmanager
def quiet_interrupts() -> Iterator[None]:
    """Ignore Ctrl-C (and SIGTERM / SIGHUP, when ours) for a while, in the main thread.

    So that stopping is not torn: a second Ctrl-C while boards are being made safe would
    otherwise interrupt that with a traceback (``Exception ignored in threading``).
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous: dict[int, Any] = {}
    for signum in _STOPPING_SIGNALS:
        with contextlib.suppress(ValueError, OSError):
            handler = signal.getsignal(signum)
            if signum == signal.SIGINT or handler is _on_terminate:
                previous[signum] = signal.signal(signum, _ignore_interrupt)
    try:
        yield
    finally:
        for signum, handler in previous.items():
            with contextlib.suppress(ValueError, OSError):
                signal.signal(signum, handler)


def _ignore_interrupt(signum: int, frame: FrameType | None) -> None:
    LOGGER.debug("%s while stopping: ignored, the boards are being made safe", signum)


# -- when: a signal ---------------------------------------------------------------------------


def on_terminate(
    loop: asyncio.AbstractEventLoop, handler: Callable[[int], None]
) -> Callable[[], None]:
    """Have SIGTERM / SIGHUP call ``handler(signum)`` in ``loop`` instead of exiting at once.

    A robot uses this to stop in order (cancel its work, make its boards safe) and then
    exit with ``128 + signum`` itself. The most recent handler wins.

    :returns: a function that removes the handler again.
    """
    entry = (loop, handler)
    with _lock:
        _terminate_handlers.append(entry)
    install()

    def remove() -> None:
        with _lock, contextlib.suppress(ValueError):
            _terminate_handlers.remove(entry)

    return remove


def _on_terminate(signum: int, frame: FrameType | None) -> None:
    global _terminating
    name = signal.Signals(signum).name
    with _lock:
        handlers = list(_terminate_handlers)
    while handlers:
        loop, handler = handlers.pop()
        if loop.is_closed():
            continue
        LOGGER.error("Terminated by %s: making every board safe.", name)
        with contextlib.suppress(RuntimeError):
            loop.call_soon_threadsafe(handler, signum)
            return
    try:
        running: asyncio.AbstractEventLoop | None = asyncio.get_running_loop()
    except RuntimeError:  # this (main) thread is not running a loop
        running = None
    if running is not None and not _terminating:
        # Raising here could tear a task in the middle of a step (a lock half released, a
        # shielded write whose wake-up is lost), and the loop's runner would then wait
        # for it for ever. Raise between two callbacks instead: the runner cancels the
        # tasks and finishes the loop, which makes its boards safe. A second signal while
        # the loop is stuck in blocking code raises at once.
        _terminating = True
        LOGGER.error("Terminated by %s: making every board safe.", name)
        running.call_soon_threadsafe(_exit, signum)
        return
    if not _terminating:
        LOGGER.error("Terminated by %s: making every board safe.", name)
    raise SystemExit(128 + signum)


def _exit(signum: int) -> None:
    raise SystemExit(128 + signum)


# -- installing -------------------------------------------------------------------------------


def install() -> None:
    """Install the exit hook, the excepthook and (from the main thread) the signal handlers.

    Idempotent; boards, robots and the sync facade call it. Signal handlers are only
    installed where nobody else installed one (the signal's action is the default).
    """
    global _installed, _signals_installed
    with _lock:
        if not _installed:
            _installed = True
            register = getattr(threading, "_register_atexit", None)
            try:
                # Runs before the interpreter joins non-daemon threads, while ports can
                # still be closed and the sync facade's loop thread still runs.
                if register is None:  # pragma: no cover - every CPython we support has it
                    raise RuntimeError
                register(_at_exit)
            except RuntimeError:  # pragma: no cover - already shutting down
                atexit.register(_at_exit)
            if sys.excepthook is _previous_excepthook:
                sys.excepthook = _excepthook
        if _signals_installed or threading.current_thread() is not threading.main_thread():
            return
        _signals_installed = True
    names = ["SIGTERM"] if sys.platform == "win32" else ["SIGTERM", "SIGHUP"]
    for name in names:
        signum = getattr(signal, name)
        with contextlib.suppress(ValueError, OSError):
            if signal.getsignal(signum) is signal.SIG_DFL:
                signal.signal(signum, _on_terminate)

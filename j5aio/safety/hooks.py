"""The process hooks: when the rescue runs, installed by the entry points.

:func:`install` puts in place, once for the whole library:

* an exit hook that runs before Python joins its threads: first the orderly exit steps
  (:func:`add_exit_step`: the sync facade's shutdown), then the rescue over every board
  still open;
* ``sys.excepthook``: an unhandled exception ends the program with its boards made safe
  before the traceback is printed (Ctrl-C prints one short line instead, unless debug
  logging is on); during game over, the program waits for game over to end it;
* SIGTERM and SIGHUP handlers (from the main thread, where nobody else installed one):
  ``SystemExit(128 + signal)``, or handed to a running
  :class:`~j5aio.robot.BaseRobot` (:func:`on_terminate`), which stops in order and exits
  the same way.

The entry points install them: :class:`~j5aio.robot.BaseRobot`, the sync facade, the
command line, and the public ways of getting boards without a robot
(:meth:`Environment.get_board_group <j5aio.backends.environment.Environment.get_board_group>`,
a backend's ``attach``). A board made directly (a test's, a backend author's) installs
nothing in the process. The end of an event loop needs no hook: a watcher task per loop
(:func:`j5aio.safety.rescue.watch`) rescues its boards.
"""

from __future__ import annotations

import asyncio
import atexit
import contextlib
import logging
import signal
import sys
import threading
from collections.abc import Callable, Iterator
from types import FrameType, TracebackType
from typing import Any, Final

from j5aio.safety import rescue
from j5aio.safety.registry import wait_for_game_over
from j5aio.safety.rescue import make_all_safe_now

__all__ = ["add_exit_step", "install", "on_terminate", "quiet_interrupts"]

LOGGER = logging.getLogger("j5aio.lifetime")  # the name teams' log settings know

_STOPPING_SIGNALS: Final = tuple(
    getattr(signal, name) for name in ("SIGINT", "SIGTERM", "SIGHUP") if hasattr(signal, name)
)

_lock = threading.RLock()
_exit_steps: list[Callable[[], None]] = []
_terminate_handlers: list[tuple[asyncio.AbstractEventLoop, Callable[[int], None]]] = []
_installed = False
_signals_installed = False
_finished = False
#: Whether a terminating signal has been asked to stop a running loop.
_terminating = False


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
            # The program is ending: a further Ctrl-C would only tear the safe stop and the
            # interpreter's own exit hooks (with a traceback), so it is ignored from now on,
            # before anything else is done.
            _ignore_further_interrupts()
            _finish("the program was stopped with Ctrl-C")
        else:
            _finish(f"the program stopped on an unhandled {kind.__name__}")
    if (
        issubclass(kind, KeyboardInterrupt)
        and not interactive
        and not logging.getLogger("j5aio").isEnabledFor(logging.DEBUG)
    ):
        if rescue.failures():
            message = "Stopped (Ctrl-C); some boards could not be made safe (see above)."
        else:
            message = "Stopped (Ctrl-C); every board was made safe."
        print(message, file=sys.stderr, flush=True)
        _ignore_further_interrupts()
        return
    _previous_excepthook(kind, value, traceback)


def _ignore_further_interrupts() -> None:
    """Ignore Ctrl-C from now on (the main thread only can say so)."""
    if threading.current_thread() is threading.main_thread():
        with contextlib.suppress(ValueError, OSError):
            signal.signal(signal.SIGINT, _ignore_interrupt)


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
            # (the sync facade may wrap ours: see j5aio.sync._deferral)
            if signum == signal.SIGINT or getattr(handler, "__wrapped__", handler) is _on_terminate:
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

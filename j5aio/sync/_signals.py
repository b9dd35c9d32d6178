"""Signals for a main thread that waits on a lock for the portal.

While a caller waits for its call it blocks on a lock with no time limit. Signals still
interrupt that wait at once, because the portal's thread (and every thread it starts:
anyio's workers, USB links) blocks SIGINT, SIGTERM and SIGHUP
(:func:`keep_signals_for_the_main_thread`), so the kernel delivers them to the waiting
main thread. A signal can still land on a thread the program started itself; then
Python's signal wake-up file (:func:`signal.set_wakeup_fd`, when nobody else uses it)
wakes whoever watches it, which has the loop release every waiting caller's lock so
that the main thread returns to Python and runs the handler. The facade's own loop
watches the file itself (:func:`watch_signals_in`): whichever thread runs the loop reads
it, and no thread is kept for it; the hand-off portal's loop thread parks while it
watches no file, so a small watcher thread does it there (:func:`start_signal_watch`).
On Windows, where a lock wait cannot be interrupted, callers wait in slices instead.
"""

from __future__ import annotations

import asyncio
import os
import signal
import sys
import threading
from collections.abc import Callable
from typing import Final

__all__ = [
    "INTERRUPTIBLE_WAIT",
    "keep_signals_for_the_main_thread",
    "start_signal_watch",
    "watch_signals_in",
]

#: Whether a lock wait is interrupted by signals (POSIX); otherwise wait in slices.
INTERRUPTIBLE_WAIT: Final = sys.platform != "win32" and hasattr(signal, "pthread_sigmask")
_SIGNALS_FOR_THE_MAIN_THREAD: Final = frozenset(
    getattr(signal, name) for name in ("SIGINT", "SIGTERM", "SIGHUP") if hasattr(signal, name)
)

#: The two ends of the pipe given as the signal wake-up file, once made: plain file
#: descriptors, open for the whole program. (Socket objects here were finalised during the
#: interpreter's shutdown, and now and then warned there that they were never closed.)
_signal_writer: int | None = None
_signal_reader: int | None = None
#: Whether a watcher thread reads ``_signal_reader`` (then no loop does).
_watched_by_a_thread = False
#: What a signal calls when it comes: wakes the current portal's callers.
_on_signal: Callable[[], None] | None = None


def keep_signals_for_the_main_thread() -> None:
    """Block SIGINT, SIGTERM and SIGHUP in this thread and the threads it starts (POSIX)."""
    if INTERRUPTIBLE_WAIT:
        signal.pthread_sigmask(signal.SIG_BLOCK, _SIGNALS_FOR_THE_MAIN_THREAD)


def _take_the_wakeup_file(on_signal: Callable[[], None]) -> int | None:
    """Make ours the signal wake-up file if it is free; return its reading end.

    ``None`` where a lock wait is not interrupted by signals, or off the main thread (which
    alone may set the file). If the program (or a running asyncio loop) uses the wake-up
    file already, it is left alone; each call takes the file back if it is free again.
    """
    global _signal_writer, _signal_reader, _on_signal
    if not INTERRUPTIBLE_WAIT or threading.current_thread() is not threading.main_thread():
        return None
    _on_signal = on_signal
    if _signal_writer is None:
        _signal_reader, _signal_writer = os.pipe()
        os.set_blocking(_signal_writer, False)  # (as the wake-up file must be)
    ours = _signal_writer
    previous = signal.set_wakeup_fd(ours, warn_on_full_buffer=False)
    if previous not in (-1, ours):  # someone else's: theirs stays
        signal.set_wakeup_fd(previous)
    return _signal_reader


def watch_signals_in(loop: asyncio.AbstractEventLoop, on_signal: Callable[[], None]) -> bool:
    """Have ``loop`` call ``on_signal`` whenever a signal lands, on whichever thread.

    The C-level handler of a Python signal handler runs in whichever thread the kernel
    chose, and writes to the signal wake-up file; the handler itself runs only in the
    main thread, which may be blocked waiting for a call. ``loop`` reads that file, in
    whichever thread runs it, and calls ``on_signal`` (which has the loop release the
    callers); no thread is started for it. Call it from the main thread, before anyone
    runs ``loop``; a loop closed later stops watching with it.

    :returns: whether ``loop`` watches the file (not where signals do not interrupt a lock
        wait, off the main thread, or when a watcher thread does already).
    """
    reader = _take_the_wakeup_file(on_signal)
    if reader is None or _watched_by_a_thread:
        return False
    os.set_blocking(reader, False)
    loop.add_reader(reader, _drain, reader)
    return True


def _drain(reader: int) -> None:
    """Read what the signals wrote, then call the current ``on_signal`` (in the loop)."""
    try:
        while os.read(reader, 64):
            pass
    except (BlockingIOError, InterruptedError):
        pass
    except OSError:  # pragma: no cover - the pipe is never closed
        return
    on_signal = _on_signal
    if on_signal is not None:
        on_signal()


def start_signal_watch(on_signal: Callable[[], None]) -> None:
    """Call ``on_signal`` whenever a signal lands, from a watcher thread (main thread only).

    As :func:`watch_signals_in`, for a portal whose loop should not watch the file: a
    daemon thread reads it, and costs nothing until a signal comes. Once it runs, it
    watches for every later portal too.
    """
    global _watched_by_a_thread
    reader = _take_the_wakeup_file(on_signal)
    if reader is None or _watched_by_a_thread:
        return
    _watched_by_a_thread = True
    os.set_blocking(reader, True)
    threading.Thread(
        target=_watch_signals, args=(reader,), name="j5aio sync signal watch", daemon=True
    ).start()


def _watch_signals(reader: int) -> None:
    """Call the current ``on_signal`` each time a signal comes (the watcher thread).

    Ends when the pipe's writing end is closed (which only tests do).
    """
    # Signals are for the main thread; this one only hears of them.
    keep_signals_for_the_main_thread()
    while os.read(reader, 64):
        on_signal = _on_signal
        if on_signal is not None:
            on_signal()

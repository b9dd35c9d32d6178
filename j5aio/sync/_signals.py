"""Signals for a main thread that waits on a lock for the portal.

While a caller waits for its call it blocks on a lock with no time limit. Signals still
interrupt that wait at once, because the portal's thread (and every thread it starts:
anyio's workers, USB links) blocks SIGINT, SIGTERM and SIGHUP
(:func:`keep_signals_for_the_main_thread`), so the kernel delivers them to the waiting
main thread. A signal can still land on a thread the program started itself; then
Python's signal wake-up file (:func:`signal.set_wakeup_fd`, when nobody else uses it)
tells a small watcher thread, which has the loop release every waiting caller's lock so
that the main thread returns to Python and runs the handler (:func:`start_signal_watch`).
On Windows, where a lock wait cannot be interrupted, callers wait in slices instead.
"""

from __future__ import annotations

import signal
import socket
import sys
import threading
from collections.abc import Callable
from typing import Final

__all__ = ["INTERRUPTIBLE_WAIT", "keep_signals_for_the_main_thread", "start_signal_watch"]

#: Whether a lock wait is interrupted by signals (POSIX); otherwise wait in slices.
INTERRUPTIBLE_WAIT: Final = sys.platform != "win32" and hasattr(signal, "pthread_sigmask")
_SIGNALS_FOR_THE_MAIN_THREAD: Final = frozenset(
    getattr(signal, name) for name in ("SIGINT", "SIGTERM", "SIGHUP") if hasattr(signal, name)
)

#: The socket our signal watcher listens to, once made (see :func:`start_signal_watch`).
_signal_writer: socket.socket | None = None
#: What the watcher calls when a signal comes: wakes the current portal's callers.
_on_signal: Callable[[], None] | None = None


def keep_signals_for_the_main_thread() -> None:
    """Block SIGINT, SIGTERM and SIGHUP in this thread and the threads it starts (POSIX)."""
    if INTERRUPTIBLE_WAIT:
        signal.pthread_sigmask(signal.SIG_BLOCK, _SIGNALS_FOR_THE_MAIN_THREAD)


def start_signal_watch(on_signal: Callable[[], None]) -> None:
    """Call ``on_signal`` whenever a signal lands, on whichever thread (main thread only).

    The C-level handler of a Python signal handler runs in whichever thread the kernel
    chose, and writes to the signal wake-up file; the handler itself runs only in the
    main thread, which may be blocked waiting for a call. A daemon thread reads that file
    and calls ``on_signal`` (which has the loop release the callers); it costs nothing
    until a signal comes. If the program (or a running asyncio loop) uses the wake-up
    file already, it is left alone; each call takes the file back if it is free again.
    """
    global _signal_writer, _on_signal
    if not INTERRUPTIBLE_WAIT or threading.current_thread() is not threading.main_thread():
        return
    _on_signal = on_signal
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
    """Call the current ``on_signal`` each time a signal comes (the watcher thread)."""
    # Signals are for the main thread; this one only hears of them.
    keep_signals_for_the_main_thread()
    with reader:
        while reader.recv(64):
            on_signal = _on_signal
            if on_signal is not None:
                on_signal()

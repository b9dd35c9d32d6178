"""One blocking call of the sync facade: its coroutine, its state, the lock its caller waits on."""

from __future__ import annotations

import threading
from collections.abc import Coroutine
from typing import Any, Final

__all__ = [
    "CANCEL_GRACE",
    "DONE",
    "QUEUED",
    "RUNNING",
    "Call",
    "new_done_lock",
    "release",
    "stopped_error",
]

#: How long an interrupted caller waits for its coroutine's cancellation to land.
CANCEL_GRACE: Final = 2.0

#: The call waits in the portal's queue.
QUEUED: Final = 0
#: The portal's worker is running the call's coroutine.
RUNNING: Final = 1
#: The call has finished: its result or error is set.
DONE: Final = 2


class Call:
    """One coroutine handed to the loop thread, and the lock its caller waits on.

    The loop thread sets :attr:`state` to done *before* releasing :attr:`done`, so a
    caller that sees "not done" knows it has not taken the lock yet. The lock may be
    one the caller reuses from call to call (the portal keeps one per thread): a caller
    that leaves early (interrupted) must then give up that lock for a new one.
    """

    __slots__ = ("coro", "done", "error", "result", "state")

    def __init__(self, coro: Coroutine[Any, Any, Any], done: threading.Lock) -> None:
        self.coro = coro
        self.done = done
        self.result: Any = None
        self.error: BaseException | None = None
        self.state = QUEUED

    def withdraw(self, reason: str) -> None:
        """Finish a call that never started, without running it (loop thread)."""
        self.coro.close()
        self.error = RuntimeError(reason)
        self.state = DONE
        release(self.done)


def new_done_lock() -> threading.Lock:
    """Return a lock that is held, for a caller to wait on until the loop releases it."""
    lock = threading.Lock()
    lock.acquire()
    return lock


def release(done: threading.Lock) -> None:
    """Release a caller's lock unless it is released already (loop thread only)."""
    # Only the loop thread releases these locks, so "held" cannot change to "released"
    # between the check and the release.
    if done.locked():
        done.release()


def stopped_error() -> RuntimeError:
    """The error of a call made after the portal stopped."""
    return RuntimeError(
        "the j5aio sync portal has stopped (the program is exiting); "
        "no more board calls can be made",
    )

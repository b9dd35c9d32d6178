"""One stream of button reads per board, however many tasks wait for a press.

A backend whose board must be asked whether its button was pressed keeps one
:class:`PressWatch` per button. Every task that waits for a press (``wait_until_pressed``,
a board's ``wait_for_start_flash``, :func:`~j5aio.competition.start.wait_for_start`, in
any number) waits on the watch, and the watch has at most one *poll stream* running: the
backend's coroutine that reads the board until it sees a press.

How it shares the stream, without a task of its own (so that it needs no task group and
stops by itself):

* the first waiter that finds no stream running *leads*: it runs the stream in its own
  task; the others wait for the watch to change;
* a press seen by the stream is recorded (by the stream's ``report`` callback, which the
  backend calls even if the leader has been cancelled meanwhile) and wakes every waiter
  that was waiting when the stream saw it: nobody misses a press that one task saw;
* a leader that is cancelled (its timeout, say) stops the stream and wakes the others,
  one of which leads a new stream at once: the others' wait goes on;
* a stream that fails (a :class:`~j5aio.errors.CommunicationError`, say) hands the same
  exception to every waiter that was waiting when it failed;
* when the last waiter leaves, no stream runs: an idle board is not read.
"""

from __future__ import annotations

from collections.abc import Awaitable, Callable
from typing import Protocol

import anyio

__all__ = ["PollStream", "PressWatch"]


class PollStream(Protocol):
    """The backend's coroutine that reads a button until it sees a press."""

    def __call__(self, report: Callable[[], None], *, fresh: bool) -> Awaitable[None]:
        """Read the button until a press is seen, call ``report()``, and return.

        :param report: call it (on the event loop) once a press is seen, even if the
            caller has been cancelled meanwhile; then return.
        :param fresh: ``True`` if nobody was waiting before this stream's waiters
            came: a board that latches presses should forget one latched before.
        :raises Exception: anything raised reaches every waiter.
        """
        ...


class PressWatch:
    """Waits for presses of one button for any number of tasks with one poll stream.

    :param stream: reads the button until a press is seen (see :class:`PollStream`).
    """

    def __init__(self, stream: PollStream) -> None:
        self._stream = stream
        self._presses = 0
        self._failures = 0
        self._error: BaseException | None = None
        self._waiters = 0
        self._leading = False
        self._fresh = True
        self._changed: anyio.Event | None = None
        self._scope: anyio.CancelScope | None = None

    @property
    def waiters(self) -> int:
        """How many tasks wait for a press now."""
        return self._waiters

    @property
    def polling(self) -> bool:
        """Whether a poll stream runs now."""
        return self._leading

    async def wait(self) -> None:
        """Return at the next press the poll stream sees (cancellable).

        :raises Exception: what the poll stream raised while this task waited.
        """
        presses, failures = self._presses, self._failures
        self._waiters += 1
        try:
            while self._presses == presses:
                if self._failures != failures:
                    assert self._error is not None
                    raise self._error
                if self._leading:
                    if self._changed is None:
                        self._changed = anyio.Event()
                    await self._changed.wait()
                    continue
                # Lead: run the poll stream in this task. (Written out here rather than
                # in a method of its own: this is the path of every wait for a button.)
                self._leading = True
                fresh, self._fresh = self._fresh, False
                try:
                    with anyio.CancelScope() as self._scope:
                        await self._stream(self._report, fresh=fresh)
                except Exception as exc:
                    self._error = exc
                    self._failures += 1
                finally:
                    self._scope = None
                    self._leading = False
                    changed, self._changed = self._changed, None
                    if changed is not None:
                        changed.set()  # the others: a press, a failure, or one to lead
        finally:
            self._waiters -= 1
            if not self._waiters:
                self._fresh = True
                self._changed = None  # never kept for a later event loop

    def _report(self) -> None:
        self._presses += 1
        if self._scope is not None:
            # The stream running now has nothing left to look for (the report may be its
            # own, or come late from the stream of a leader that was cancelled).
            self._scope.cancel()
        changed, self._changed = self._changed, None
        if changed is not None:
            changed.set()

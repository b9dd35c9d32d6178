"""The match timer: at the end of a match, every board is made safe and the program ends.

A :class:`MatchTimer` is a watchdog thread, so it works whatever the robot's code does
meanwhile: a loop that swallows ``CancelledError`` or ``BaseException``, or a tight
synchronous loop that never yields to the event loop (async code or the sync facade).
When the match ends it

1. asks the robot's event loop to cancel the robot's work (a well-behaved program
   unwinds in order);
2. makes every open board safe and closes its port at once, through the boards' own
   links, with the library's one rescue (:func:`j5aio.safety.rescue.make_all_safe_now`):
   from the loop if it answers within :data:`LOOP_WAIT` seconds, else from this thread;
   closing the ports means nothing the program still sends reaches a board;
3. logs ``Game over``, runs the :func:`add_game_over_hook` hooks and, after
   :data:`GRACE` seconds, goes over the boards once more, flushes the output and ends the
   process with status 0 (``os._exit``: no user code can hold it back).

From the moment game over begins, no board can be opened any more (opening one raises
:class:`~j5aio.errors.GameOverError`), so a program cannot drive again in the grace; and
a program that ends meanwhile, by an exception from a board closed under it or by
reaching its end, waits for game over to end the process, so it ends with "Game over"
and status 0 (:func:`j5aio.safety.registry.wait_for_game_over`). Nothing in the program
can stop the timer. What a program in the same interpreter can still hold back (C code that keeps
the GIL, a huge switch interval, a forked child) is ended by the match supervisor of
``j5aio run``, outside the program's interpreter.
"""

from __future__ import annotations

import contextlib
import logging
import os
import sys
import threading
import time
from collections.abc import Callable
from typing import Final, TextIO

from j5aio.safety import registry, rescue

__all__ = ["GRACE", "LOOP_WAIT", "MatchTimer", "add_game_over_hook"]

LOGGER = logging.getLogger(__name__)

#: The most seconds the boards' event loop gets to start making them safe itself.
LOOP_WAIT: Final = 0.005
#: The seconds a program gets to end by itself after game over, boards already safe.
GRACE: Final = 0.25
#: The GIL switch interval from just before game over on, so that a busy thread cannot
#: hold the watchdog back for long (Python's default is 5 ms).
_SWITCH_INTERVAL: Final = 0.0005
#: How many times game over goes over the boards still open.
_PASSES: Final = 3
#: How long before the end the switch interval is shortened, in seconds.
_GET_READY: Final = 0.1

_hooks: list[Callable[[], None]] = []


def add_game_over_hook(hook: Callable[[], None]) -> None:
    """Run ``hook()`` at game over, after the boards are safe and before the process ends.

    For things that must happen even though the process ends with ``os._exit`` (a
    competition's scoring record, a test's record of the boards). A hook that raises is
    logged and skipped.
    """
    if hook not in _hooks:
        _hooks.append(hook)


class MatchTimer:
    """A watchdog thread that ends the match after ``duration`` real seconds.

    :param duration: real seconds from :meth:`start` to game over (more than 0).
    :param cancel: called (from the watchdog thread) to cancel the robot's work; it must
        be thread-safe, e.g. ``lambda: loop.call_soon_threadsafe(scope.cancel)``.
    :param end_process: ends the process with a status (``os._exit``; tests replace it).
    :param grace: seconds the program gets to end by itself after the boards are safe.
    :raises ValueError: ``duration`` is not more than 0.
    """

    def __init__(
        self,
        duration: float,
        *,
        cancel: Callable[[], None] | None = None,
        end_process: Callable[[int], object] = os._exit,
        grace: float = GRACE,
    ) -> None:
        if not duration > 0:
            raise ValueError(f"the match duration must be more than 0 seconds, not {duration}")
        self._duration = duration
        self._cancel = cancel
        self._end_process = end_process
        self._grace = grace
        self._stopped = threading.Event()
        self._thread = threading.Thread(target=self._run, name="j5aio match timer", daemon=True)
        self._ends_at: float | None = None
        #: The monotonic time the match ended at (``None`` until game over).
        self.ended_at: float | None = None

    @property
    def ends_at(self) -> float | None:
        """The ``time.monotonic()`` at which the match ends; ``None`` before :meth:`start`."""
        return self._ends_at

    def remaining(self) -> float | None:
        """Real seconds left in the match; ``None`` before :meth:`start`."""
        if self._ends_at is None:
            return None
        return max(self._ends_at - time.monotonic(), 0.0)

    def start(self) -> None:
        """Start the match now.

        :raises RuntimeError: it was started already.
        """
        if self._ends_at is not None:
            raise RuntimeError("the match timer was started already")
        self._ends_at = time.monotonic() + self._duration
        self._thread.start()
        from j5aio.competition import supervisor

        supervisor.report_start(self._ends_at)  # game over from outside, if supervised
        LOGGER.info("The match has started: it ends in %g s.", self._duration)

    def _disarm(self) -> None:
        """Stop the watchdog without game over (for tests of the library only).

        A program has no way to stop the match: game over always comes.
        """
        self._stopped.set()

    def join(self, timeout: float | None = None) -> None:
        """Wait for the watchdog thread to finish (after game over)."""
        if self._thread.is_alive():
            self._thread.join(timeout)

    def _run(self) -> None:
        assert self._ends_at is not None
        ready = False
        while not self._stopped.is_set():
            left = self._ends_at - time.monotonic()
            if left <= 0:
                self.game_over()
                return
            if left <= _GET_READY and not ready:
                ready = True
                sys.setswitchinterval(_SWITCH_INTERVAL)
            self._stopped.wait(left if ready else left - _GET_READY)

    def game_over(self) -> None:
        """End the match now (see the module's documentation for what happens)."""
        self.ended_at = time.monotonic()
        sys.setswitchinterval(_SWITCH_INTERVAL)
        registry.begin_game_over()  # from now on no board can be opened
        if self._cancel is not None:
            try:
                self._cancel()
            except Exception as exc:  # the loop closed meanwhile: nothing to cancel
                LOGGER.debug("Could not cancel the robot's work: %r", exc)
        for board in registry.open_boards():
            registry.mark_settled(board)  # the end of a match is no program's mistake
        _make_safe_and_close()
        from j5aio.competition import supervisor

        supervisor.report_safe()
        LOGGER.warning("Game over: the match has ended and every board is safe.")
        for hook in list(_hooks):
            try:
                hook()
            except Exception as exc:
                LOGGER.error("A game-over hook failed: %r", exc)
        time.sleep(self._grace)
        _make_safe_and_close()  # a board opened before game over began, driven meanwhile
        _flush()
        try:
            self._end_process(0)
        finally:
            registry.end_game_over()


def _make_safe_and_close() -> None:
    """Make every open board safe and close its port, in up to :data:`_PASSES` passes."""
    # A board whose port fails to close stops the pass it is in (it is forgotten first),
    # so the boards after it get another pass.
    for _ in range(_PASSES):
        try:
            rescue.make_all_safe_now("the match ended", close=True, loop_wait=LOOP_WAIT)
        except Exception as exc:
            LOGGER.error("Making the boards safe at game over failed: %r", exc)
        if not registry.open_boards():
            break


def _flush() -> None:
    flushable: list[logging.Handler | TextIO] = [
        *logging.getLogger().handlers,
        *logging.getLogger("j5aio").handlers,
        sys.stdout,
        sys.stderr,
    ]
    for item in flushable:
        with contextlib.suppress(Exception):  # a broken stream must not stop the exit
            item.flush()

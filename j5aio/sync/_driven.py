"""The facade's event loop, run by the thread that makes the blocking call.

There is one asyncio loop per process and, at any moment, at most one thread runs it: its
*driver*. A small state machine (one :class:`threading.Condition`) says who that is:

* **Nobody** (idle): the program is in its own code, between two calls.
* **A caller.** A blocking call that finds the loop idle takes it and runs the loop
  itself until its coroutine is done (``run_forever``, stopped by the loop's worker task
  when the call ends), then leaves it idle again. Nothing else is woken on this path: no
  thread hand-off at all.
* **The keeper**, a daemon thread that runs the loop while no caller does, so that the
  background work of a program (the match timer, the robot service's client, the live
  view, reconnections, worker threads' results) goes on while the program sleeps or
  computes. It takes the loop once it has been idle for :data:`GRACE`, or at once when
  calls made from other threads are waiting. While calls keep coming it looks only every
  :data:`LOOK_AGAIN` (a thread that woke every few milliseconds was measured to slow
  each call of the main thread by several microseconds), so a program that leaves the
  calls has the keeper take over within ``LOOK_AGAIN + GRACE``; a caller that finds it
  driving asks it to stop (``call_soon_threadsafe(loop.stop)``) and takes the loop when
  it has. While a caller drives a long call, the keeper sleeps with no time limit.

A call from a thread that finds *another caller* driving is queued for the loop's worker,
as the hand-off portal does (:mod:`j5aio.sync._loop_thread`), and its thread waits on a
lock; the driver hands the loop to the keeper when its own call ends, so that such calls
never wait for the grace. The loop's one worker task runs every call in turn (a call made
from another thread never overtakes one being run), inside an anyio cancel scope: a
cancelled call stops at its next checkpoint and shielded transport exchanges stay whole.

Signals are for the main thread, which may be driving: see :mod:`j5aio.sync._deferral`.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import threading
import time
from collections import deque
from collections.abc import Callable, Coroutine
from typing import Any, Final

import anyio

from j5aio.backends.acknowledgements import acknowledge_later
from j5aio.safety.hooks import quiet_interrupts
from j5aio.sync._calls import (
    CANCEL_GRACE,
    DONE,
    QUEUED,
    RUNNING,
    Call,
    new_done_lock,
    release,
    stopped_error,
)
from j5aio.sync._deferral import SignalDeferral, current_handler
from j5aio.sync._signals import keep_signals_for_the_main_thread, watch_signals_in

__all__ = ["GRACE", "LOOK_AGAIN", "NESTED_CALL", "DrivenLoop"]


def _logger() -> logging.Logger:
    """The facade's logger, looked up when something goes wrong: a start makes none."""
    return logging.getLogger("j5aio.sync")


#: How long the loop may stay idle (the program in its own code) before the keeper runs it.
GRACE: Final = 0.015
#: While calls keep coming, how often the keeper looks whether they have stopped.
LOOK_AGAIN: Final = 0.25

#: What a blocking call made from async code running in the facade's loop is told.
NESTED_CALL: Final = (
    "a blocking j5aio.sync call was made from async code running in the sync "
    "portal's loop; await the async API (j5aio) there instead"
)
_STOPPING: Final = "the board call was cancelled: the j5aio sync portal is stopping"

#: The lock of a call whose caller drives the loop: nobody waits on it, nobody takes it.
_NOBODY_WAITS: Final = threading.Lock()


def _stop_soon(loop: asyncio.AbstractEventLoop) -> None:
    """Ask ``loop`` to stop, from any thread or a signal handler (harmless once closed)."""
    with contextlib.suppress(RuntimeError):
        loop.call_soon_threadsafe(loop.stop)


class DrivenLoop:
    """The facade's event loop, its worker task, its keeper thread and who drives it.

    :param grace: how long the loop stays idle before the keeper runs it (:data:`GRACE`).
    :param on_signal: called in the loop whenever a signal lands on any thread, if given:
        the loop watches the signal wake-up file itself (see
        :func:`~j5aio.sync._signals.watch_signals_in`), so no thread does.
    """

    def __init__(
        self, *, grace: float = GRACE, on_signal: Callable[[], None] | None = None
    ) -> None:
        self.loop = asyncio.SelectorEventLoop()
        #: Whether the loop watches the signal wake-up file (``on_signal`` was given, and
        #: the file could be had).
        self.watches_signals = on_signal is not None and watch_signals_in(self.loop, on_signal)
        self.grace = grace
        #: While calls keep coming, how often the keeper looks whether they have stopped.
        self.look_again = max(grace, LOOK_AGAIN)
        self._queue: deque[Call] = deque()
        self._current: Call | None = None
        self._driven: Call | None = None
        #: The threads seen calling from inside an event loop of their own, with that loop.
        self._in_other_loops: dict[int, asyncio.AbstractEventLoop] = {}
        #: The finished call object of the last call run by its own caller, to use again.
        self._spare: Call | None = None
        self._scope: anyio.CancelScope | None = None
        self._waiter: asyncio.Future[None] | None = None
        self._stopping = False
        self._mutex = threading.Lock()
        self._turns = threading.Condition(self._mutex)
        #: The ident of the thread that drives the loop, or None while it is idle.
        self._owner: int | None = None
        self._left_at = time.monotonic()
        self._keeper_sleeps = False
        #: How many calls have ended: the keeper tells a long call from many short ones.
        self._calls = 0
        self._stop_asked = False
        self._closing = False
        self._main_ident = threading.main_thread().ident
        self.deferral = SignalDeferral(self._stop_for_signal)
        self._root = self.loop.create_task(self._main())
        self.thread = threading.Thread(
            target=self._keep, name="j5aio sync loop keeper", daemon=True
        )
        self.thread.start()

    # -- the worker (in whichever thread drives the loop) ---------------------------------

    async def _main(self) -> None:
        """Run the queued calls in turn, each in the current cancel scope, until stopped.

        The loop's root task: anyio ties its worker threads to it, so they live as long.
        A scope that has cancelled a call is replaced; the next call gets a fresh one.
        """
        # The facade's calls confirm acknowledgements later: a student's command returns
        # once its bytes are written, and the board's reply is checked before its next
        # request (j5aio.backends.acknowledgements). The switch is set in this task's
        # context, which every call run here shares.
        with acknowledge_later():
            queue = self._queue
            while not self._stopping:
                with anyio.CancelScope() as scope:
                    self._scope = scope
                    while not scope.cancel_called and not self._stopping:
                        if not queue:
                            self._waiter = waiter = self.loop.create_future()
                            try:
                                await waiter
                            finally:
                                self._waiter = None
                            continue
                        request = queue.popleft()
                        self._current = request
                        request.state = RUNNING
                        try:
                            request.result = await request.coro
                        except BaseException as exc:
                            if scope.cancel_called and isinstance(
                                exc, anyio.get_cancelled_exc_class()
                            ):
                                request.error = RuntimeError(_STOPPING)
                                raise  # to the scope, which ends here
                            request.error = exc
                        finally:
                            self._current = None
                            request.state = DONE
                            if request is self._driven:
                                self._driven = None
                                self.loop.stop()  # the caller driving the loop has its result
                            else:
                                release(request.done)
            while queue:
                queue.popleft().withdraw(_STOPPING)

    def _wake(self) -> None:
        waiter = self._waiter
        if waiter is not None and not waiter.done():
            waiter.set_result(None)

    def _cancel(self, request: Call) -> None:
        """Cancel ``request`` (in the loop): withdrawn if queued, its scope if running."""
        if request.state == QUEUED:
            with contextlib.suppress(ValueError):
                self._queue.remove(request)
                request.withdraw("the board call was cancelled before it started")
                if request is self._driven:
                    self._driven = None
                    self.loop.stop()
        elif request is self._current and self._scope is not None:
            self._scope.cancel()

    def _cancel_current(self) -> None:
        if self._current is not None and self._scope is not None:
            self._scope.cancel()

    def _let_callers_check_signals(self) -> None:
        """Release the lock of every caller waiting in another thread, not marking done.

        Each then finds its call not done and waits again, after its thread has run any
        signal handler that was pending (see :mod:`j5aio.sync._signals`).
        """
        current = self._current
        if current is not None and current is not self._driven:
            release(current.done)
        for request in self._queue:
            release(request.done)

    def _stop_for_signal(self) -> None:
        _stop_soon(self.loop)

    # -- callers -------------------------------------------------------------------------

    def run(self, coro: Coroutine[Any, Any, Any], wait: Callable[[DrivenLoop, Call], Any]) -> Any:
        """Run ``coro`` to its end and return its result (or raise its exception).

        The calling thread drives the loop itself if nobody else does (and stops the
        keeper for that); if another caller drives it, ``coro`` is queued and ``wait``
        (given this loop and the queued call) waits for it and returns its result.

        :raises RuntimeError: called from async code running in this loop, or the loop
            has been closed.
        """
        me = threading.get_ident()
        if self._owner == me:  # only this thread could have made itself the driver
            coro.close()
            raise RuntimeError(NESTED_CALL)
        main = me == self._main_ident
        deferral = self.deferral
        if main:
            for signum, handler in deferral.seen:  # (a program may install its own later)
                if current_handler(signum) is not handler:
                    deferral.install()
                    break
            deferral.active = True
        if self._in_other_loops and self._runs_another_loop(me):
            if main:
                deferral.active = False
            return self._queue_for_the_keeper(coro, wait)
        try:
            with self._mutex:
                taken = self._owner is None and not self._closing
                if taken:
                    self._owner = me
        except BaseException:  # pragma: no cover - signals are deferred here
            coro.close()
            raise
        if not taken:
            taken, result = self._take_slowly(coro, me, main, wait)
            if not taken:
                return result
        # This thread owns the loop: run it until the worker has run the call.
        loop = self.loop
        request = self._spare
        if request is None:
            request = Call(coro, _NOBODY_WAITS)
        else:  # the call object of the last call this way, finished: used again
            self._spare = None
            request.coro = coro
            request.state = QUEUED
        elsewhere = False
        try:
            try:
                self._driven = request
                self._queue.append(request)
                waiter = self._waiter
                if waiter is not None and not waiter.done():
                    waiter.set_result(None)  # the worker's turn, as soon as the loop runs
                while request.state != DONE:
                    try:
                        loop.run_forever()
                    except RuntimeError:
                        if request.state != QUEUED or loop.is_closed():
                            raise
                        # This thread runs another event loop: the keeper runs the call
                        # (and this thread's next ones, as long as that loop runs).
                        self._in_other_loops[me] = asyncio.get_running_loop()
                        self._driven = None
                        request.done = new_done_lock()
                        elsewhere = True
                        break
                    if main and deferral.pending:
                        deferral.run_pending()  # a handler that raises ends the call
            except BaseException:
                self._abandon(request)
                raise
            finally:
                self._leave(main)
        except BaseException:
            deferral.pending.clear()  # later signals of the same stop: ignored as ever
            raise
        if elsewhere:
            return wait(self, request)
        if main and deferral.pending:  # a signal that came as the call ended
            deferral.run_pending()
        result, error = request.result, request.error
        request.result = request.error = None
        self._spare = request
        if error is not None:
            try:
                raise error
            finally:
                del error
        return result

    def _abandon(self, request: Call) -> None:
        """Cancel this thread's call and drive the loop until it stops, within the grace."""
        if request.state == DONE:
            return
        loop = self.loop
        with quiet_interrupts():
            loop.call_soon(self._cancel, request)
            deadline = time.monotonic() + CANCEL_GRACE
            expiry = loop.call_later(CANCEL_GRACE, loop.stop)
            try:
                while request.state != DONE and time.monotonic() < deadline:
                    loop.run_forever()
            finally:
                expiry.cancel()
        if request.state != DONE:
            self._driven = None  # the keeper runs it on to its end
            _logger().error("A cancelled board call did not stop within %.1f s.", CANCEL_GRACE)

    def _leave(self, main: bool) -> None:
        """Leave the loop idle; wake the keeper if calls of other threads are waiting."""
        with self._mutex:
            self._owner = None
            self._left_at = time.monotonic()
            self._calls += 1
            if self._keeper_sleeps or self._queue or self._current is not None or self._closing:
                self._turns.notify_all()
        if main:
            self.deferral.active = False

    def _runs_another_loop(self, me: int) -> bool:
        """Whether thread ``me`` is inside an event loop of its own (seen at a past call)."""
        other = self._in_other_loops.get(me)
        if other is None:
            return False
        if other.is_running():  # (and so in this thread: it was, and this thread is busy)
            return True
        del self._in_other_loops[me]
        return False

    def _queue_for_the_keeper(
        self, coro: Coroutine[Any, Any, Any], wait: Callable[[DrivenLoop, Call], Any]
    ) -> Any:
        """Queue a call for whoever drives the loop (the keeper, if nobody), and wait.

        The driver runs it when the calls before it are done; a caller that drives hands
        the loop to the keeper when its own call ends, so the call never waits for the
        grace.
        """
        with self._mutex:
            if self._closing:
                coro.close()
                raise stopped_error()
            request = Call(coro, new_done_lock())
            self._queue.append(request)
            if self._owner is None:
                self._turns.notify_all()  # the keeper takes the loop at once
        with contextlib.suppress(RuntimeError):
            self.loop.call_soon_threadsafe(self._wake)
        return wait(self, request)

    def _take_slowly(
        self,
        coro: Coroutine[Any, Any, Any],
        me: int,
        main: bool,
        wait: Callable[[DrivenLoop, Call], Any],
    ) -> tuple[bool, Any]:
        """The loop was not idle: take it from the keeper, or queue for another caller.

        :returns: ``(True, None)`` once this thread owns the loop, or ``(False, result)``
            when another thread's turn ran the call.
        """
        try:
            with self._mutex:
                while True:
                    if self._closing:
                        raise stopped_error()
                    owner = self._owner
                    if owner is None:
                        self._owner = me
                        return True, None
                    if owner != self.thread.ident:  # another caller: queue for its turn
                        break
                    if not self._stop_asked:
                        self._stop_asked = True
                        _stop_soon(self.loop)
                    if main:  # Ctrl-C interrupts the wait, as any lock wait
                        self.deferral.active = False
                        self.deferral.run_pending()
                    self._turns.wait()
                    if main:
                        self.deferral.active = True
        except BaseException:
            if main:
                self.deferral.active = False
            coro.close()
            raise
        if main:
            self.deferral.active = False
            try:
                self.deferral.run_pending()  # (a signal that came meanwhile raises here)
            except BaseException:
                coro.close()
                raise
        return False, self._queue_for_the_keeper(coro, wait)

    # -- the keeper thread -----------------------------------------------------------------

    def _keep(self) -> None:
        # Signals are for the main thread; threads started while the keeper drives (anyio's
        # workers) inherit this mask.
        keep_signals_for_the_main_thread()
        me = threading.get_ident()
        turns = self._turns
        seen = -1
        while True:
            with self._mutex:
                while True:
                    if self._closing:
                        return
                    idle = 0.0
                    if self._owner is None:
                        if self._queue or self._current is not None:
                            break
                        idle = self._left_at + self.grace - time.monotonic()
                        if idle <= 0:
                            break
                    if self._calls != seen:
                        # Calls come and go: look again later, waking nobody. (Not every
                        # grace: a thread that wakes that often slows the calls of the
                        # main thread by several microseconds each, measured.)
                        seen = self._calls
                        turns.wait(self.look_again)
                    elif self._owner is None:
                        turns.wait(idle)
                    else:
                        # One call has lasted a whole grace (a wait for a button, say):
                        # sleep with no time limit; its caller wakes the keeper at its end.
                        self._keeper_sleeps = True
                        turns.wait()
                        self._keeper_sleeps = False
                self._owner = me
            self._drive_as_keeper()

    def _drive_as_keeper(self) -> None:
        """Run the loop until a caller (or the close) asks for it, then leave it idle."""
        try:
            while True:
                try:
                    self.loop.run_forever()
                except Exception:  # pragma: no cover - asyncio handles callbacks' errors
                    _logger().exception("The sync facade's event loop failed")
                except BaseException as exc:  # a task raised SystemExit, say
                    _logger().error("The sync facade's event loop was stopped by %r", exc)
                with self._mutex:
                    if self._stop_asked or self._closing:
                        break  # (a stop nobody asked for, a stale one: drive on)
        finally:
            with self._mutex:
                self._owner = None
                self._stop_asked = False
                self._left_at = time.monotonic()  # the caller's turn now, not the keeper's
                self._turns.notify_all()

    # -- other threads --------------------------------------------------------------------

    @property
    def current(self) -> Call | None:
        """The call the worker is running, if any."""
        return self._current

    def wake_callers(self) -> None:
        """Have every waiting caller, and a main thread driving, check for signals."""
        with contextlib.suppress(RuntimeError):
            self.loop.call_soon_threadsafe(self._let_callers_check_signals)

    def cancel(self, request: Call) -> None:
        """Cancel ``request`` (from a thread waiting for it); it finishes soon after."""
        with contextlib.suppress(RuntimeError):
            self.loop.call_soon_threadsafe(self._cancel, request)

    def close(self, last: Coroutine[Any, Any, Any], timeout: float) -> BaseException | None:
        """Take the loop, run ``last`` (making the boards safe), then stop and close it all.

        Whoever drives the loop at that moment: the keeper is asked to stop, and a call
        another thread is driving is cancelled (it raises the portal's "stopping" error).
        ``last`` and the worker's end get ``timeout`` seconds each.

        :returns: ``last``'s exception, if it raised one.
        :raises TimeoutError: the loop could not be taken, or ``last`` did not finish.
        """
        me = threading.get_ident()
        if self._owner == me:
            last.close()
            raise RuntimeError(NESTED_CALL)
        if self.loop.is_closed():  # closed before: nothing left to do
            last.close()
            return None
        deadline = time.monotonic() + timeout
        with self._mutex:
            self._closing = True
            current = self._current
            if current is not None:  # another thread's call: it ends with "stopping"
                self.cancel(current)
            while self._owner is not None:
                if self._owner == self.thread.ident and not self._stop_asked:
                    self._stop_asked = True
                    _stop_soon(self.loop)
                remaining = deadline - time.monotonic()
                if remaining <= 0:
                    last.close()
                    raise TimeoutError("a blocking call kept the sync facade's loop")
                self._turns.wait(remaining)
            self._owner = me
        main = me == self._main_ident
        if main:
            self.deferral.active = True  # (signals while the boards are made safe: ignored)
        try:
            return self._finish(last, deadline + timeout)
        finally:
            if main:
                self.deferral.active = False
                self.deferral.pending.clear()
                self.deferral.uninstall()
            with self._mutex:
                self._owner = None
                self._turns.notify_all()
            self.thread.join(timeout)

    def _finish(self, last: Coroutine[Any, Any, Any], deadline: float) -> BaseException | None:
        loop = self.loop
        request = Call(last, _NOBODY_WAITS)
        try:
            self._driven = request
            self._queue.append(request)
            self._wake()
            expiry = loop.call_later(max(deadline - time.monotonic(), 0), loop.stop)
            try:
                while request.state != DONE and time.monotonic() < deadline:
                    loop.run_forever()
            finally:
                expiry.cancel()
            if request.state != DONE:
                self._driven = None
                raise TimeoutError("the boards were not made safe in time")
            self._stopping = True
            self._cancel_current()
            self._wake()
            self._run_until(self._root, deadline)
            tasks = asyncio.all_tasks(loop)
            for task in tasks:
                task.cancel()
            if tasks:
                self._run_until(asyncio.gather(*tasks, return_exceptions=True), deadline)
            loop.run_until_complete(loop.shutdown_asyncgens())
            return request.error
        finally:
            self._stopping = True
            while self._queue:
                self._queue.popleft().withdraw(_STOPPING)
            loop.close()

    def _run_until(self, future: asyncio.Future[Any], deadline: float) -> None:
        """Drive the loop (this thread owns it) until ``future`` is done or ``deadline``."""
        loop = self.loop
        future.add_done_callback(lambda _: loop.stop())
        expiry = loop.call_later(max(deadline - time.monotonic(), 0), loop.stop)
        try:
            while not future.done() and time.monotonic() < deadline:
                loop.run_forever()
        finally:
            expiry.cancel()

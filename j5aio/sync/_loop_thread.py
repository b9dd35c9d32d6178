"""The portal's thread: an event loop and one worker task that runs the calls in turn.

One persistent worker task runs the calls one after another, so no task and no cancel
scope are made per call (the worker's scope is replaced only after it has been used to
cancel a call). A call costs two thread wake-ups: the caller rings the loop, which hands
the call to its worker in the same turn (:attr:`~j5aio.sync._selectors.HookedSelector.after_wait`),
and the caller is let go just before the loop sleeps again
(:attr:`~j5aio.sync._selectors.HookedSelector.before_wait`), so that it does not then wait
for the GIL as well. Cancelling a call cancels the worker's anyio cancel scope, so
shielded transport exchanges stay whole.
"""

from __future__ import annotations

import asyncio
import contextlib
import sys
import threading
from collections import deque
from collections.abc import Callable, Coroutine
from typing import Any, TypeVar

import anyio

from j5aio.backends.acknowledgements import acknowledge_later
from j5aio.sync._calls import DONE, QUEUED, RUNNING, Call, new_done_lock, release, stopped_error
from j5aio.sync._selectors import CAN_PARK, HookedSelector, ParkingLoop, ParkingSelector
from j5aio.sync._signals import keep_signals_for_the_main_thread

__all__ = ["LoopThread"]

T = TypeVar("T")

_STOPPING = "the board call was cancelled: the j5aio sync portal is stopping"


class LoopThread:
    """The background thread, its event loop and its worker; started when made.

    :param park: whether the loop sleeps on a lock while it watches no file
        (:class:`~j5aio.sync._selectors.ParkingSelector`); by default wherever it can.
    """

    def __init__(self, *, park: bool = CAN_PARK) -> None:
        self._queue: deque[Call] = deque()
        self._finished: list[Call] = []
        self._current: Call | None = None
        self._scope: anyio.CancelScope | None = None
        self._waiter: asyncio.Future[None] | None = None
        self._idle = False
        self._stopping = False
        self.loop: asyncio.AbstractEventLoop
        self._defer_release = True
        if park:
            parking = ParkingSelector()
            self.loop = ParkingLoop(parking)
            self._hook(parking)
            self._ring: Callable[[], None] = parking.ring
        elif sys.platform != "win32":
            hooked = HookedSelector()
            self.loop = asyncio.SelectorEventLoop(hooked)
            self._hook(hooked)
            self._ring = self._wake_threadsafe
        else:  # pragma: no cover - Windows: a proactor loop, which has no selector
            self.loop = asyncio.new_event_loop()
            self._ring = self._wake_threadsafe
            self._defer_release = False
        ready = threading.Event()
        self.thread = threading.Thread(
            target=self._run, args=(ready,), name="j5aio sync portal", daemon=True,
        )
        self.thread.start()
        ready.wait()

    def _hook(self, selector: HookedSelector) -> None:
        selector.before_wait = self._release_finished
        selector.after_wait = self._hand_over

    # -- the loop thread ----------------------------------------------------------------

    def _run(self, ready: threading.Event) -> None:
        # Signals go to the main thread, whose lock wait they interrupt; the threads this
        # one starts inherit the mask.
        keep_signals_for_the_main_thread()
        asyncio.set_event_loop(self.loop)
        try:
            self.loop.run_until_complete(self._main(ready))
            self._cancel_remaining_tasks()
            self.loop.run_until_complete(self.loop.shutdown_asyncgens())
        finally:
            self.loop.close()
            self._stopping = True
            self._withdraw_queued()
            self._release_finished()

    def _cancel_remaining_tasks(self) -> None:
        # As asyncio.run does: tasks left (the safety net's watcher among them) end now.
        tasks = asyncio.all_tasks(self.loop)
        for task in tasks:
            task.cancel()
        if tasks:
            self.loop.run_until_complete(asyncio.gather(*tasks, return_exceptions=True))

    async def _main(self, ready: threading.Event) -> None:
        # This task is the loop's root task: anyio ties its worker threads to it, so they
        # stop when it returns.
        ready.set()
        with acknowledge_later():  # as in the caller-driven loop (see j5aio.sync._driven)
            while not self._stopping:
                with anyio.CancelScope() as scope:
                    self._scope = scope
                    await self._serve(scope)
        self._withdraw_queued()
        self._release_finished()

    def _withdraw_queued(self) -> None:
        while self._queue:
            self._queue.popleft().withdraw(_STOPPING)

    async def _serve(self, scope: anyio.CancelScope) -> None:
        """Run calls until the portal stops or ``scope`` has cancelled one."""
        # A stop that lands while the worker waits for a call must not let a call start.
        while not scope.cancel_called and not self._stopping:
            request = self._queue.popleft() if self._queue else await self._next()
            if request is None:
                return
            self._current = request
            request.state = RUNNING
            try:
                request.result = await request.coro
            except BaseException as exc:
                if scope.cancel_called and isinstance(exc, anyio.get_cancelled_exc_class()):
                    request.error = RuntimeError(_STOPPING)
                    raise  # to the scope, which ends here; the next call gets a new one
                request.error = exc
            finally:
                self._current = None
                request.state = DONE
                if self._defer_release:
                    # Released when the loop next waits: see _selectors.HookedSelector.
                    self._finished.append(request)
                else:  # pragma: no cover - Windows
                    release(request.done)

    def _release_finished(self) -> None:
        """Let the callers of finished calls go (loop thread, as the loop is about to wait)."""
        finished = self._finished
        while finished:
            release(finished.pop().done)

    async def _next(self) -> Call | None:
        while not self._stopping:
            self._idle = True
            if self._queue:  # appended after the check above, before _idle was set
                self._idle = False
                return self._queue.popleft()
            self._waiter = self.loop.create_future()
            try:
                await self._waiter
            finally:
                self._idle = False
                self._waiter = None
            if self._queue and not self._stopping:
                return self._queue.popleft()
        return None

    def _wake(self) -> None:
        waiter = self._waiter
        if waiter is not None and not waiter.done():
            waiter.set_result(None)

    def _hand_over(self) -> None:
        """Wake the idle worker if a call is queued (loop thread, after each wait)."""
        if self._queue:
            self._wake()

    def _let_callers_check_signals(self) -> None:
        """Release the lock of every caller still waiting (loop thread), not marking done.

        Each caller then finds its call not done and waits again, after its thread has
        run any signal handler that was pending (see :mod:`j5aio.sync._signals`).
        """
        if self._current is not None:
            release(self._current.done)
        for request in self._queue:
            release(request.done)

    def _wake_threadsafe(self) -> None:
        self.loop.call_soon_threadsafe(self._wake)

    def _cancel(self, request: Call) -> None:
        if request.state == QUEUED:
            with contextlib.suppress(ValueError):
                self._queue.remove(request)
                request.withdraw("the board call was cancelled before it started")
        elif request is self._current and self._scope is not None:
            self._scope.cancel()

    def _begin_stop(self) -> None:
        self._stopping = True
        if self._current is not None and self._scope is not None:
            self._scope.cancel()
        self._wake()

    # -- other threads --------------------------------------------------------------------

    @property
    def current(self) -> Call | None:
        """The call the worker is running, if any."""
        return self._current

    def submit(
        self, coro: Coroutine[Any, Any, T], done: threading.Lock | None = None
    ) -> Call:
        """Queue ``coro`` for the worker (from any thread but the loop's).

        ``done`` is the held lock to release when the call has finished (a new one if not
        given); the caller waits on it.
        """
        if self._stopping or self.loop.is_closed():
            coro.close()
            raise stopped_error()
        request = Call(coro, new_done_lock() if done is None else done)
        self._queue.append(request)
        if self._idle:
            try:
                self._ring()
            except RuntimeError:  # pragma: no cover - the loop closed in this instant
                self._take_back(request)
        if self._stopping:  # stopped meanwhile: the loop withdraws it, or we take it back
            self._take_back(request)
        return request

    def _take_back(self, request: Call) -> None:
        try:
            self._queue.remove(request)
        except ValueError:
            return  # withdrawn by the loop: the caller finds the reason in its error
        request.coro.close()
        raise stopped_error() from None

    def wake_callers(self) -> None:
        """Have every waiting caller check for signals (from any thread but the loop's)."""
        with contextlib.suppress(RuntimeError):
            self.loop.call_soon_threadsafe(self._let_callers_check_signals)

    def cancel(self, request: Call) -> None:
        """Cancel ``request`` (from any thread but the loop's); it finishes soon after."""
        with contextlib.suppress(RuntimeError):
            self.loop.call_soon_threadsafe(self._cancel, request)

    def stop(self, timeout: float) -> None:
        """Stop the loop (from any thread other than the loop's) and join the thread."""
        if self.thread.is_alive():
            with contextlib.suppress(RuntimeError):
                self.loop.call_soon_threadsafe(self._begin_stop)
            self.thread.join(timeout)

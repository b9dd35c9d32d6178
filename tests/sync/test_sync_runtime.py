"""The portal: results, errors, cancellation when the caller is interrupted, restart."""

from __future__ import annotations

import asyncio
import functools
import inspect
import os
import signal
import socket
import threading
import time
from collections.abc import Awaitable, Callable, Iterator

import anyio
import anyio.lowlevel
import anyio.to_thread
import pytest

from j5aio.sync import _loop_thread, _runtime, _signals
from j5aio.sync._calls import DONE, Call, new_done_lock
from j5aio.sync._driven import DrivenLoop
from j5aio.sync._loop_thread import LoopThread
from j5aio.sync._runtime import call, get_loop, shutdown
from j5aio.sync._selectors import CAN_PARK, ParkingLoop

#: The kinds of portal loop: parking on a lock where asyncio allows, and the plain one
#: (the fallback where it does not), which must keep every promise alike.
LOOP_KINDS = [
    pytest.param(True, id="parking", marks=pytest.mark.skipif(not CAN_PARK, reason="no parking")),
    pytest.param(False, id="plain"),
]


async def add(a: int, b: int, *, c: int = 0) -> int:
    await anyio.lowlevel.checkpoint()
    return a + b + c


async def fail() -> None:
    raise ValueError("bad value: allowed are 1 to 3")


def test_call_returns_the_coroutines_result() -> None:
    assert call(add, 1, 2) == 3
    assert call(add, 1, 2, c=3) == 6


def test_call_runs_in_the_calling_thread_which_drives_the_loop() -> None:
    async def where() -> tuple[threading.Thread, asyncio.AbstractEventLoop]:
        return threading.current_thread(), asyncio.get_running_loop()

    thread, loop = call(where)
    assert thread is threading.current_thread()
    assert loop is get_loop()
    assert not loop.is_running()  # between calls, nobody (or the keeper, later) runs it


@pytest.mark.usefixtures("handoff_portal")
def test_call_runs_in_the_portal_thread() -> None:
    async def where() -> threading.Thread:
        return threading.current_thread()

    thread = call(where)
    assert thread is not threading.current_thread()
    assert thread.daemon
    assert get_loop().is_running()


def test_call_reraises_the_coroutines_exception() -> None:
    with pytest.raises(ValueError, match="allowed are 1 to 3"):
        call(fail)


def test_call_refuses_a_function_that_is_not_a_coroutine_function() -> None:
    def plain() -> int:
        return 1

    with pytest.raises(TypeError, match="did not return a coroutine"):
        call(plain)  # type: ignore[arg-type]


def test_call_from_inside_the_portal_loop_is_refused() -> None:
    async def nested() -> int:
        return call(add, 1, 1)

    with pytest.raises(RuntimeError, match="await the async API"):
        call(nested)


def ctrl_c() -> None:
    """Send SIGINT to the main thread, as the terminal's Ctrl-C reaches a sync program."""
    main = threading.main_thread().ident
    assert main is not None
    signal.pthread_kill(main, signal.SIGINT)


def interrupt_main_after(delay: float) -> threading.Timer:
    timer = threading.Timer(delay, ctrl_c)
    timer.start()
    return timer


def recorded_command(
    events: list[str], seconds: float, cleanup: float | None = None
) -> Callable[[], Awaitable[None]]:
    """Return a command that takes ``seconds`` and records what became of it in ``events``.

    Cancelled, it cleans up for ``cleanup`` seconds (shielded) when that is given.
    """

    async def motor_command() -> None:
        events.append("started")
        try:
            await anyio.sleep(seconds)
            events.append("completed")
        except anyio.get_cancelled_exc_class():
            events.append("cancelled")
            if cleanup is not None:
                with anyio.CancelScope(shield=True):
                    await anyio.sleep(cleanup)  # cleaning up takes a moment
                events.append("cleaned up")
            raise

    return motor_command


def test_interrupt_cancels_the_coroutine_before_the_call_returns() -> None:
    events: list[str] = []
    motor_command = recorded_command(events, 5, cleanup=0.1)

    interrupt_main_after(0.1)
    with pytest.raises(KeyboardInterrupt):
        call(motor_command)
    assert events == ["started", "cancelled", "cleaned up"]
    time.sleep(0.2)
    assert events == ["started", "cancelled", "cleaned up"]


def test_cancellation_respects_anyio_shields() -> None:
    events: list[str] = []

    async def exchange() -> None:
        with anyio.CancelScope(shield=True):
            await anyio.sleep(0.3)
            events.append("exchange whole")
        await anyio.sleep(5)
        events.append("completed")

    interrupt_main_after(0.05)
    with pytest.raises(KeyboardInterrupt):
        call(exchange)
    assert events == ["exchange whole"]


@pytest.mark.parametrize("park", LOOP_KINDS)
def test_call_cancelled_before_it_starts_never_runs(park: bool) -> None:
    ran: list[bool] = []
    portal = LoopThread(park=park)
    blocker = threading.Event()

    async def busy() -> None:
        await anyio.to_thread.run_sync(blocker.wait)

    async def never() -> None:
        ran.append(True)

    first = portal.submit(busy())
    second = portal.submit(never())
    portal.cancel(second)
    assert second.done.acquire(timeout=2)
    blocker.set()
    assert first.done.acquire(timeout=2)
    portal.stop(2)
    assert ran == []
    assert isinstance(second.error, RuntimeError)
    assert "before it started" in str(second.error)


@pytest.mark.parametrize("park", LOOP_KINDS)
def test_portal_that_has_stopped_refuses_new_calls(park: bool) -> None:
    portal = LoopThread(park=park)
    portal.stop(2)
    assert not portal.thread.is_alive()

    async def never() -> None:
        raise AssertionError("ran")

    with pytest.raises(RuntimeError, match="portal has stopped"):
        portal.submit(never())


@pytest.mark.parametrize("park", LOOP_KINDS)
def test_stopping_a_portal_cancels_calls_still_running(park: bool) -> None:
    portal = LoopThread(park=park)
    request = portal.submit(anyio.sleep(10))
    time.sleep(0.05)
    portal.stop(2)
    assert request.done.acquire(timeout=1)
    assert isinstance(request.error, RuntimeError)
    assert "portal is stopping" in str(request.error)


def test_shutdown_then_call_starts_a_new_portal() -> None:
    first = get_loop()
    shutdown()
    assert not first.is_running()
    shutdown()  # twice is harmless
    assert call(add, 2, 2) == 4
    assert get_loop() is not first


def test_a_caller_woken_before_its_call_is_done_waits_on() -> None:
    async def wakes_its_caller_early() -> int:
        portal = _runtime._portal
        assert portal is not None
        for _ in range(3):
            portal._let_callers_check_signals()  # as when a signal came
            await anyio.sleep(0.01)
        return 7

    assert call(wakes_its_caller_early) == 7
    assert call(add, 1, 1) == 2  # and the thread's lock is in order afterwards


class RecordingLock:
    """A caller's lock that records the time limit of every wait on it."""

    def __init__(self) -> None:
        self.lock = new_done_lock()
        self.timeouts: list[float] = []

    def acquire(self, blocking: bool = True, timeout: float = -1) -> bool:
        self.timeouts.append(timeout)
        return self.lock.acquire(blocking, timeout)

    def locked(self) -> bool:
        return self.lock.locked()

    def release(self) -> None:
        self.lock.release()


@pytest.mark.parametrize("park", LOOP_KINDS)
def test_a_waiting_caller_sleeps_until_woken_with_no_periodic_wake_up(park: bool) -> None:
    portal = LoopThread(park=park)
    try:
        lock = RecordingLock()
        request = portal.submit(anyio.sleep(0.3), lock)  # type: ignore[arg-type]
        assert _runtime._wait(portal, request) is None
        assert lock.timeouts == [-1]  # one wait, with no time limit
    finally:
        portal.stop(2)


def test_a_signal_that_lands_on_another_thread_still_cancels_the_call() -> None:
    shutdown()  # a new portal takes the signal wake-up file back if a test's loop freed it
    events: list[str] = []
    motor_command = recorded_command(events, 30)

    def ctrl_c_on_this_thread() -> None:
        # Not the main thread: only the signal watcher can wake the main thread's wait.
        signal.pthread_kill(threading.get_ident(), signal.SIGINT)

    call(add, 0, 0)
    assert _signals._signal_writer is not None
    timer = threading.Timer(0.1, ctrl_c_on_this_thread)
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        call(motor_command)
    timer.join()
    assert events == ["started", "cancelled"]


def test_a_signal_wake_up_file_of_the_program_is_left_alone() -> None:
    call(add, 0, 0)
    theirs, peer = socket.socketpair()
    theirs.setblocking(False)
    try:
        previous = signal.set_wakeup_fd(theirs.fileno())
        _signals.start_signal_watch(_runtime._wake_waiting_callers)
        assert signal.set_wakeup_fd(previous) == theirs.fileno()
    finally:
        theirs.close()
        peer.close()


@pytest.fixture
def fresh_signal_watch(monkeypatch: pytest.MonkeyPatch) -> Iterator[None]:
    """The signal watch as in a new program: no wake-up socket yet, no watcher thread."""
    shutdown()
    theirs = _signals._signal_writer
    before = set(threading.enumerate())
    monkeypatch.setattr(_signals, "_signal_writer", None)
    monkeypatch.setattr(_signals, "_signal_reader", None)
    monkeypatch.setattr(_signals, "_watched_by_a_thread", False)
    yield
    shutdown()
    signal.set_wakeup_fd(theirs if theirs is not None else -1)
    if _signals._signal_writer is not None:
        os.close(_signals._signal_writer)  # a watcher thread's read ends
    for thread in set(threading.enumerate()) - before:
        if thread.name == "j5aio sync signal watch":
            thread.join(5)
    if _signals._signal_reader is not None:
        os.close(_signals._signal_reader)


@pytest.mark.usefixtures("fresh_signal_watch")
def test_the_callers_loop_hears_of_signals_itself_and_no_watcher_thread_starts() -> None:
    before = set(threading.enumerate())
    call(add, 0, 0)
    portal = _runtime._portal
    assert isinstance(portal, DrivenLoop)
    assert portal.watches_signals
    started = {thread.name for thread in set(threading.enumerate()) - before}
    assert started == {"j5aio sync loop keeper"}
    events: list[str] = []

    def ctrl_c_on_this_thread() -> None:
        signal.pthread_kill(threading.get_ident(), signal.SIGINT)  # not the main thread

    timer = threading.Timer(0.1, ctrl_c_on_this_thread)
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        call(recorded_command(events, 30))
    timer.join()
    assert events == ["started", "cancelled"]


@pytest.mark.usefixtures("fresh_signal_watch")
def test_once_a_watcher_thread_reads_the_wake_up_file_no_loop_does() -> None:
    calls: list[str] = []
    _signals.start_signal_watch(lambda: calls.append("first portal"))
    assert any(t.name == "j5aio sync signal watch" for t in threading.enumerate())
    loop = asyncio.new_event_loop()
    try:
        assert not _signals.watch_signals_in(loop, lambda: calls.append("new portal"))
    finally:
        loop.close()  # (a loop that watched the file would have read it first)
    assert _signals._signal_writer is not None
    os.write(_signals._signal_writer, b"x")  # as the C-level handler of a signal does
    deadline = time.monotonic() + 5
    while not calls and time.monotonic() < deadline:
        time.sleep(0.01)
    assert calls == ["new portal"]  # the thread wakes the current portal's callers


@pytest.mark.usefixtures("fresh_signal_watch")
def test_a_loop_watching_the_wake_up_file_calls_on_signal_for_what_was_written() -> None:
    calls: list[str] = []
    loop = asyncio.new_event_loop()
    try:
        assert _signals.watch_signals_in(loop, lambda: calls.append("loop"))
        assert _signals._signal_writer is not None
        os.write(_signals._signal_writer, b"xyz")
        loop.run_until_complete(asyncio.sleep(0.05))
        assert calls == ["loop"]  # once for all it read
    finally:
        loop.close()


@pytest.mark.usefixtures("fresh_signal_watch")
def test_off_the_main_thread_no_loop_watches_the_wake_up_file() -> None:
    loop = asyncio.new_event_loop()
    results: list[bool] = []
    try:
        thread = threading.Thread(
            target=lambda: results.append(_signals.watch_signals_in(loop, lambda: None))
        )
        thread.start()
        thread.join()
    finally:
        loop.close()
    assert results == [False]
    assert _signals._signal_writer is None


class InterruptedJustAfterAcquiring:
    """A lock whose first acquire succeeds and is then interrupted, as by a late Ctrl-C."""

    def __init__(self, lock: threading.Lock) -> None:
        self.lock = lock
        self.calls = 0

    def acquire(self, blocking: bool = True, timeout: float = -1) -> bool:
        self.calls += 1
        taken = self.lock.acquire(blocking, timeout)
        if self.calls == 1:
            assert taken
            raise KeyboardInterrupt
        return taken


@pytest.mark.parametrize("park", LOOP_KINDS)
def test_an_interrupt_just_after_the_call_finished_does_not_wait(
    caplog: pytest.LogCaptureFixture, park: bool,
) -> None:
    portal = LoopThread(park=park)
    try:
        request = portal.submit(add(1, 2))
        deadline = time.monotonic() + 2
        while request.state != DONE:
            assert time.monotonic() < deadline
            time.sleep(0.001)
        late = InterruptedJustAfterAcquiring(request.done)
        request.done = late  # type: ignore[assignment]
        with pytest.raises(KeyboardInterrupt):
            _runtime._wait(portal, request)
        assert late.calls == 1  # no second wait (of CANCEL_GRACE): the lock was ours
        assert "did not stop" not in caplog.text
    finally:
        portal.stop(2)


def test_the_worker_keeps_serving_after_a_cancelled_call() -> None:
    interrupt_main_after(0.05)
    with pytest.raises(KeyboardInterrupt):
        call(anyio.sleep, 5)
    assert call(add, 2, 3) == 5  # a fresh cancel scope: the next call is not cancelled
    assert call(add, 4, 3) == 7


@pytest.mark.parametrize("park", LOOP_KINDS)
def test_calls_still_queued_when_the_portal_stops_are_refused(park: bool) -> None:
    portal = LoopThread(park=park)
    first = portal.submit(anyio.sleep(5))
    queued = portal.submit(add(1, 1))
    portal.stop(2)
    assert first.done.acquire(timeout=1) and queued.done.acquire(timeout=1)
    assert isinstance(queued.error, RuntimeError)
    assert "portal is stopping" in str(queued.error)


def test_shutdown_cancels_a_call_in_progress_in_another_thread() -> None:
    errors: list[BaseException] = []

    def caller() -> None:
        try:
            call(anyio.sleep, 5)
        except RuntimeError as exc:
            errors.append(exc)

    get_loop()
    thread = threading.Thread(target=caller)
    thread.start()
    time.sleep(0.1)
    shutdown()
    thread.join(10)  # liveness only: the 5 s sleep would end it too, but with no error
    assert not thread.is_alive()
    assert len(errors) == 1 and "portal is stopping" in str(errors[0])


def test_a_failure_to_make_boards_safe_at_shutdown_is_logged(
    monkeypatch: pytest.MonkeyPatch, caplog: pytest.LogCaptureFixture
) -> None:
    async def broken(timeout: float) -> None:
        raise OSError("the registry is broken")

    monkeypatch.setattr(_runtime, "make_all_safe_uncancellably", broken)
    get_loop()
    shutdown()
    assert "Could not make the boards safe: OSError('the registry is broken')" in caplog.text


def test_shutdown_waits_for_the_boards_even_when_a_signal_wakes_it(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # A signal makes the loop release every waiting caller's lock so that it can run the
    # handler; shutdown once took that release for "boards safe" and stopped the loop in
    # the middle of closing them (a SIGTERM during a blocking call, seen in CI).
    finished: list[str] = []

    async def slow_safe_state(timeout: float) -> None:
        await anyio.sleep(0.3)
        finished.append("safe")

    monkeypatch.setattr(_runtime, "make_all_safe_uncancellably", slow_safe_state)
    portal = _runtime._get_portal()

    def signal_arrives() -> None:
        time.sleep(0.1)
        portal.wake_callers()

    waker = threading.Thread(target=signal_arrives)
    waker.start()
    shutdown()
    waker.join()
    assert finished == ["safe"]
    assert not portal.thread.is_alive()


@pytest.mark.parametrize("park", LOOP_KINDS)
def test_a_call_queued_as_the_portal_stops_is_taken_back_or_left_withdrawn(park: bool) -> None:
    portal = LoopThread(park=park)
    portal.stop(2)
    coro = add(1, 1)
    queued = Call(coro, new_done_lock())
    portal._queue.append(queued)  # as if appended just after the stop was seen
    with pytest.raises(RuntimeError, match="portal has stopped"):
        portal._take_back(queued)
    assert not portal._queue
    assert inspect.getcoroutinestate(coro) == inspect.CORO_CLOSED  # closed, never run
    withdrawn = Call(add(2, 2), new_done_lock())
    withdrawn.withdraw("the board call was cancelled: the j5aio sync portal is stopping")
    portal._take_back(withdrawn)  # the loop got there first: the caller reads its error
    assert withdrawn.done.acquire(timeout=1)
    assert isinstance(withdrawn.error, RuntimeError)


@pytest.fixture
def plain_portal(monkeypatch: pytest.MonkeyPatch) -> Iterator[None]:
    """The facade's portal on the plain event loop, as where asyncio's loop cannot park."""
    shutdown()
    monkeypatch.setattr(_loop_thread, "LoopThread", functools.partial(LoopThread, park=False))
    yield
    shutdown()


@pytest.mark.usefixtures("plain_portal")
def test_the_plain_loop_keeps_the_promises_of_the_parking_one() -> None:
    loop = get_loop()
    assert not isinstance(loop, ParkingLoop)
    assert [call(add, n, 1) for n in range(20)] == list(range(1, 21))
    with pytest.raises(ValueError, match="allowed are 1 to 3"):
        call(fail)
    # A worker thread's result comes back through call_soon_threadsafe.
    assert call(anyio.to_thread.run_sync, time.sleep, 0.001) is None
    events: list[str] = []
    interrupt_main_after(0.1)
    with pytest.raises(KeyboardInterrupt):
        call(recorded_command(events, 5, cleanup=0.1))
    assert events == ["started", "cancelled", "cleaned up"]
    assert call(add, 2, 3) == 5  # the worker serves on after a cancelled call
    assert get_loop() is loop

"""The loop its callers drive: the keeper, calls from other threads, signals, exit."""

from __future__ import annotations

import asyncio
import signal
import threading
import time
from collections.abc import Awaitable, Callable, Iterator
from types import FrameType

import anyio
import anyio.lowlevel
import anyio.to_thread
import pytest

from j5aio.safety import hooks
from j5aio.sync import _deferral, _driven, _runtime
from j5aio.sync._deferral import DeferringHandler, SignalDeferral
from j5aio.sync._driven import DrivenLoop
from j5aio.sync._loop_thread import LoopThread
from j5aio.sync._runtime import call, get_loop, shutdown

pytestmark = pytest.mark.skipif(not _runtime.CALLER_DRIVES, reason="callers drive on POSIX")

#: A liveness bound, not a speed goal: only a hang waits this long.
LIVENESS = 10.0


async def add(a: int, b: int) -> int:
    await anyio.lowlevel.checkpoint()
    return a + b


@pytest.fixture
def portal() -> Iterator[DrivenLoop]:
    """A fresh caller-driven portal for the test, shut down after it."""
    shutdown()
    made = _runtime._get_portal()
    assert isinstance(made, DrivenLoop)
    yield made
    shutdown()


def wait_until(condition: Callable[[], bool]) -> None:
    deadline = time.monotonic() + LIVENESS
    while not condition():
        assert time.monotonic() < deadline, "gave up waiting"
        time.sleep(0.001)


def signal_main(signum: int) -> None:
    main = threading.main_thread().ident
    assert main is not None
    signal.pthread_kill(main, signum)


def signal_main_when(event: threading.Event, signum: int) -> threading.Thread:
    """Start a thread that signals the main thread once ``event`` is set."""

    def send() -> None:
        if event.wait(LIVENESS):
            signal_main(signum)

    sender = threading.Thread(target=send)
    sender.start()
    return sender


def test_the_keeper_runs_the_loop_while_the_program_is_away_from_calls(
    portal: DrivenLoop,
) -> None:
    ran = threading.Event()
    seen: list[object] = []

    def in_the_loop() -> None:
        seen.append(threading.current_thread())
        try:
            call(add, 1, 1)  # from the keeper's own turn: refused, as from any loop code
        except RuntimeError as exc:
            seen.append(str(exc))
        ran.set()

    async def schedule() -> None:
        asyncio.get_running_loop().call_later(0.05, in_the_loop)

    call(schedule)
    assert ran.wait(LIVENESS)  # no call is made meanwhile: only the keeper runs the loop
    assert seen[0] is portal.thread
    assert "await the async API" in str(seen[1])
    assert call(add, 2, 3) == 5  # and a caller takes the loop back from the keeper


def test_the_keeper_does_not_wake_for_each_call_while_calls_keep_coming(
    portal: DrivenLoop, monkeypatch: pytest.MonkeyPatch
) -> None:
    # A thread that wakes every few milliseconds slows every call of the main thread: while
    # calls come, the keeper looks again only every `look_again`, whatever the grace.
    waits: list[float | None] = []
    real_wait = portal._turns.wait

    def counted(timeout: float | None = None) -> bool:
        waits.append(timeout)
        return real_wait(timeout)

    portal.grace = 0.001
    portal.look_again = LIVENESS
    monkeypatch.setattr(portal._turns, "wait", counted)
    with portal._turns:
        portal._turns.notify_all()  # the keeper looks again, now with the patched wait
    for _ in range(2000):
        assert call(add, 1, 1) == 2
    assert len(waits) <= 3, waits
    assert all(timeout in (None, LIVENESS) for timeout in waits[1:]), waits


def test_a_call_from_another_thread_waits_for_the_driving_call_then_runs(
    portal: DrivenLoop,
) -> None:
    driving = threading.Event()
    gate = threading.Event()
    results: list[object] = []

    async def long_call() -> str:
        driving.set()
        await anyio.to_thread.run_sync(gate.wait)
        return "long"

    def second_caller() -> None:
        assert driving.wait(LIVENESS)
        results.append(call(add, 1, 2))
        results.append(threading.current_thread() is not threading.main_thread())

    def open_the_gate() -> None:
        wait_until(lambda: bool(portal._queue))  # the second call waits its turn
        gate.set()

    second = threading.Thread(target=second_caller)
    opener = threading.Thread(target=open_the_gate)
    second.start()
    opener.start()
    assert call(long_call) == "long"
    # No more calls from here: the keeper takes the loop at once for the queued call.
    second.join(LIVENESS)
    opener.join(LIVENESS)
    assert results == [3, True]


def recorded(
    events: list[str], gate: threading.Event | None = None
) -> Callable[[], Awaitable[None]]:
    async def motor_command() -> None:
        events.append("started")
        try:
            if gate is not None:
                gate.set()
            await anyio.sleep(30)
            events.append("completed")
        except anyio.get_cancelled_exc_class():
            events.append("cancelled")
            raise

    return motor_command


def test_ctrl_c_during_a_driven_call_cancels_it_and_raises_at_its_boundary(
    portal: DrivenLoop,
) -> None:
    events: list[str] = []
    started = threading.Event()
    sender = signal_main_when(started, signal.SIGINT)
    with pytest.raises(KeyboardInterrupt) as raised:
        call(recorded(events, started))
    sender.join()
    assert events == ["started", "cancelled"]
    # Raised by the handler, run outside the loop's code: no asyncio frame below the call.
    frames = [frame.f_code.co_filename for frame, _ in _walk(raised.value.__traceback__)]
    assert not any("asyncio" in name for name in frames)
    assert isinstance(signal.getsignal(signal.SIGINT), DeferringHandler)
    assert call(add, 1, 1) == 2


def _walk(traceback: object) -> Iterator[tuple[FrameType, int]]:
    import traceback as tb

    return tb.walk_tb(traceback)  # type: ignore[arg-type]


@pytest.fixture
def safety_net_sigterm(monkeypatch: pytest.MonkeyPatch) -> Iterator[None]:
    """SIGTERM handled by the safety net (raising SystemExit), as in a program."""
    monkeypatch.setattr(hooks, "_terminating", False)
    monkeypatch.setattr(hooks, "_terminate_handlers", [])
    previous = signal.signal(signal.SIGTERM, hooks._on_terminate)
    yield
    signal.signal(signal.SIGTERM, previous)


@pytest.mark.usefixtures("safety_net_sigterm")
def test_sigterm_during_a_driven_call_exits_at_its_boundary(portal: DrivenLoop) -> None:
    events: list[str] = []
    started = threading.Event()
    sender = signal_main_when(started, signal.SIGTERM)
    with pytest.raises(SystemExit) as raised:
        call(recorded(events, started))
    sender.join()
    assert raised.value.code == 128 + signal.SIGTERM
    assert events == ["started", "cancelled"]
    assert not portal.loop.is_running() or portal._owner == portal.thread.ident
    assert call(add, 2, 2) == 4


@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM], ids=["SIGINT", "SIGTERM"])
@pytest.mark.usefixtures("safety_net_sigterm")
def test_a_signal_during_the_keepers_turn_raises_where_the_program_is(
    portal: DrivenLoop, signum: int
) -> None:
    keeper_ran = threading.Event()

    async def schedule() -> None:
        asyncio.get_running_loop().call_later(0.05, keeper_ran.set)

    call(schedule)
    assert keeper_ran.wait(LIVENESS)  # the keeper drives now
    waiting = threading.Event()
    go = threading.Event()
    sender = signal_main_when(go, signum)
    go.set()
    with pytest.raises((KeyboardInterrupt, SystemExit)):
        waiting.wait(LIVENESS)  # the program's own code, outside any call
    sender.join()
    assert call(add, 3, 4) == 7  # the loop is whole: the caller takes it from the keeper


def test_a_handler_the_program_installs_later_runs_outside_the_loop(portal: DrivenLoop) -> None:
    call(add, 0, 0)
    handled: list[object] = []
    release = threading.Event()

    def program_handler(signum: int, frame: FrameType | None) -> None:
        try:
            asyncio.get_running_loop()
            handled.append("inside the loop")
        except RuntimeError:
            handled.append("outside the loop")
        release.set()  # handled, and the call goes on to its end

    previous = signal.signal(signal.SIGINT, program_handler)
    try:
        started = threading.Event()

        async def waits_for_the_handler() -> str:
            started.set()
            await anyio.to_thread.run_sync(release.wait)
            return "finished"

        sender = signal_main_when(started, signal.SIGINT)
        assert call(waits_for_the_handler) == "finished"
        sender.join()
        assert handled == ["outside the loop"]
        wrapper = signal.getsignal(signal.SIGINT)
        assert isinstance(wrapper, DeferringHandler)
        assert wrapper.__wrapped__ is program_handler
        assert "program_handler" in repr(wrapper)
    finally:
        signal.signal(signal.SIGINT, previous)


def test_a_call_from_a_thread_running_another_loop_is_run_by_the_keeper(
    portal: DrivenLoop,
) -> None:
    results: list[object] = []

    async def where() -> threading.Thread:
        return threading.current_thread()

    async def other_program() -> None:
        # Blocking calls block this loop, as they always did; the keeper runs them.
        results.append(call(add, 20, 22))
        results.append(call(where) is portal.thread)
        results.append(call(add, 1, 1))  # (known now to run a loop: queued at once)

    def program() -> None:
        asyncio.run(other_program())
        results.append(call(where) is threading.current_thread())  # its loop ended: drives

    thread = threading.Thread(target=program)
    thread.start()
    thread.join(LIVENESS)
    assert results == [42, True, 2, True]
    assert portal._in_other_loops == {}


def test_exit_while_the_keeper_drives_makes_the_boards_safe(
    portal: DrivenLoop, monkeypatch: pytest.MonkeyPatch
) -> None:
    made_safe: list[object] = []

    async def record_safe(timeout: float) -> None:
        made_safe.append(threading.current_thread())

    monkeypatch.setattr(_runtime, "make_all_safe_uncancellably", record_safe)
    keeper_ran = threading.Event()

    async def schedule() -> None:
        asyncio.get_running_loop().call_later(0.05, keeper_ran.set)

    call(schedule)
    assert keeper_ran.wait(LIVENESS)
    shutdown()
    assert made_safe == [threading.main_thread()]  # taken from the keeper, run here
    assert portal.loop.is_closed()
    assert not portal.thread.is_alive()
    assert get_loop() is not portal.loop  # a new one on demand


def test_a_closed_portal_refuses_calls(portal: DrivenLoop) -> None:
    assert portal.close(add(1, 1), 2) is None
    coro = add(1, 2)
    with pytest.raises(RuntimeError, match="portal has stopped"):
        portal.run(coro, _runtime._wait)


def test_the_signal_handlers_are_checked_cheaply_or_with_the_public_function(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    assert _deferral._find_current_handler()(signal.SIGINT) is signal.getsignal(signal.SIGINT)

    def missing(name: str) -> object:
        raise ImportError(name)

    monkeypatch.setattr("importlib.import_module", missing)
    assert _deferral._find_current_handler() is signal.getsignal
    monkeypatch.setattr(_deferral, "current_handler", signal.getsignal)
    stops: list[bool] = []
    deferral = SignalDeferral(lambda: stops.append(True))
    seen: list[int] = []
    previous = signal.signal(signal.SIGINT, lambda signum, frame: seen.append(signum))
    try:
        deferral.install()
        wrapper = signal.getsignal(signal.SIGINT)
        assert isinstance(wrapper, DeferringHandler)
        deferral.install()  # unchanged: left as it is
        assert signal.getsignal(signal.SIGINT) is wrapper
        deferral.active = True
        signal.raise_signal(signal.SIGINT)
        assert seen == [] and stops == [True]  # deferred: recorded, the loop asked to stop
        deferral.active = False
        deferral.run_pending()
        assert seen == [signal.SIGINT]
        signal.raise_signal(signal.SIGINT)  # outside a driven call: handled at once
        assert seen == [signal.SIGINT, signal.SIGINT]
        deferral.uninstall()
        assert signal.getsignal(signal.SIGINT) is wrapper.__wrapped__
    finally:
        signal.signal(signal.SIGINT, previous)


def test_a_handler_that_raises_drops_the_signals_after_it() -> None:
    deferral = SignalDeferral(lambda: None)

    def raising(signum: int, frame: FrameType | None) -> None:
        raise KeyboardInterrupt

    later: list[int] = []
    deferral.pending += [(raising, 2, None), (lambda s, f: later.append(s), 15, None)]
    with pytest.raises(KeyboardInterrupt):
        deferral.run_pending()
    assert deferral.pending == [] and later == []


@pytest.mark.usefixtures("safety_net_sigterm")
def test_quiet_interrupts_quiets_the_safety_nets_handler_when_wrapped() -> None:
    deferral = SignalDeferral(lambda: None)
    deferral.install()
    try:
        wrapper = signal.getsignal(signal.SIGTERM)
        assert isinstance(wrapper, DeferringHandler)
        with hooks.quiet_interrupts():
            signal.raise_signal(signal.SIGTERM)  # would raise SystemExit otherwise
        assert signal.getsignal(signal.SIGTERM) is wrapper
    finally:
        deferral.uninstall()


def test_ctrl_c_while_waiting_for_another_threads_turn_withdraws_the_call(
    portal: DrivenLoop,
) -> None:
    driving = threading.Event()
    gate = threading.Event()
    ran: list[str] = []

    async def long_call() -> None:
        driving.set()
        await anyio.to_thread.run_sync(gate.wait)

    async def never() -> None:
        ran.append("ran")

    other = threading.Thread(target=call, args=(long_call,))
    other.start()
    assert driving.wait(LIVENESS)
    queued = threading.Event()
    sender = signal_main_when(queued, signal.SIGINT)

    def when_queued() -> None:
        wait_until(lambda: bool(portal._queue))
        queued.set()

    threading.Thread(target=when_queued).start()
    with pytest.raises(KeyboardInterrupt):
        call(never)  # queued behind the other thread's call: withdrawn before it starts
    sender.join()
    gate.set()
    other.join(LIVENESS)
    assert ran == []
    assert portal.current is None
    assert call(add, 1, 1) == 2


def test_a_call_that_outlives_its_cancel_grace_is_finished_by_the_keeper(
    portal: DrivenLoop, monkeypatch: pytest.MonkeyPatch, caplog: pytest.LogCaptureFixture
) -> None:
    monkeypatch.setattr(_driven, "CANCEL_GRACE", 0.05)
    events: list[str] = []
    cleaned = threading.Event()
    started = threading.Event()

    async def slow_to_stop() -> None:
        started.set()
        try:
            await anyio.sleep(30)
        finally:
            with anyio.CancelScope(shield=True):
                await anyio.sleep(0.2)  # longer than the grace
            events.append("cleaned up")
            cleaned.set()

    sender = signal_main_when(started, signal.SIGINT)
    with pytest.raises(KeyboardInterrupt):
        call(slow_to_stop)
    sender.join()
    assert "did not stop within" in caplog.text
    assert cleaned.wait(LIVENESS)  # the keeper ran it on to its end
    assert events == ["cleaned up"]
    assert call(add, 1, 2) == 3


def test_the_keeper_drives_on_when_loop_code_raises_system_exit(
    portal: DrivenLoop, caplog: pytest.LogCaptureFixture
) -> None:
    after = threading.Event()

    def exits() -> None:
        raise SystemExit(3)

    async def schedule() -> None:
        loop = asyncio.get_running_loop()
        loop.call_later(0.05, exits)
        loop.call_later(0.1, after.set)

    call(schedule)
    assert after.wait(LIVENESS)
    assert "stopped by SystemExit(3)" in caplog.text
    assert call(add, 2, 2) == 4


@pytest.mark.usefixtures("handoff_portal")
def test_the_hand_off_portal_keeps_its_promises_through_call() -> None:
    assert isinstance(_runtime._get_portal(), LoopThread)
    assert [call(add, n, 1) for n in range(5)] == [1, 2, 3, 4, 5]

    async def fail() -> None:
        raise ValueError("bad value")

    with pytest.raises(ValueError, match="bad value"):
        call(fail)
    with pytest.raises(TypeError, match="did not return a coroutine"):
        call(lambda: 1)  # type: ignore[arg-type, return-value]

    async def nested() -> int:
        return call(add, 1, 1)

    with pytest.raises(RuntimeError, match="await the async API"):
        call(nested)
    events: list[str] = []
    started = threading.Event()
    sender = signal_main_when(started, signal.SIGINT)
    with pytest.raises(KeyboardInterrupt):
        call(recorded(events, started))
    sender.join()
    assert events == ["started", "cancelled"]


def test_ctrl_c_while_waiting_for_a_busy_keeper_to_give_the_loop_back(
    portal: DrivenLoop,
) -> None:
    entered = threading.Event()
    gate = threading.Event()

    def blocks_the_keeper() -> None:
        entered.set()
        gate.wait(LIVENESS)  # loop code that blocks (a bug of the program's, say)

    async def schedule() -> None:
        asyncio.get_running_loop().call_later(0.05, blocks_the_keeper)

    call(schedule)
    assert entered.wait(LIVENESS)
    asked = threading.Event()

    def when_asked() -> None:
        wait_until(lambda: portal._stop_asked)
        asked.set()

    watcher = threading.Thread(target=when_asked)
    watcher.start()
    sender = signal_main_when(asked, signal.SIGINT)
    try:
        with pytest.raises(KeyboardInterrupt):
            call(add, 1, 1)  # waits for the keeper, which cannot stop yet
    finally:
        gate.set()
    watcher.join()
    sender.join()
    assert call(add, 2, 2) == 4

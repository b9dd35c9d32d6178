"""The safety net's mechanism, in process: which boards, which thread, bounds, logs, hooks.

Whole programs ending in each way are tested in ``tests/test_lifetime.py``.
"""

from __future__ import annotations

import asyncio
import logging
import signal
import sys
import threading
import time
from collections.abc import Iterator

import anyio.to_thread
import pytest

from j5aio import lifetime
from j5aio.errors import CommunicationError, GameOverError
from j5aio.safety import hooks, registry, rescue

from .conftest import LampBackend, LampBoard


class NetLampBackend(LampBackend):
    """A lamp backend with a synchronous safe state that records where it ran."""

    def __init__(self, *, fails: bool = False, delay: float = 0.0) -> None:
        super().__init__()
        self.fails = fails
        self.delay = delay
        self.safe_now_threads: list[threading.Thread] = []
        self.closed_now = False

    def make_safe_now(self, timeout: float) -> bool:
        self.safe_now_threads.append(threading.current_thread())
        if self.delay:
            time.sleep(self.delay)
        if self.fails:
            raise CommunicationError("the lamp board did not answer")
        self.states[0] = False
        return True

    def close_now(self) -> None:
        self.closed_now = True


@pytest.fixture(autouse=True)
def _only_these_boards(monkeypatch: pytest.MonkeyPatch) -> Iterator[None]:
    """Let the net see only the boards a test makes."""
    monkeypatch.setattr(registry, "_open", {})
    monkeypatch.setattr(registry, "_settled", set())
    monkeypatch.setattr(rescue, "_failures", 0)
    monkeypatch.setattr(hooks, "_terminating", False)
    # The real excepthook ignores further Ctrl-C once the program is ending: give the
    # rest of the test run its Ctrl-C back.
    handler = signal.getsignal(signal.SIGINT)
    yield
    signal.signal(signal.SIGINT, handler)


def lamp(serial: str = "L", **kwargs: float | bool) -> tuple[LampBoard, NetLampBackend]:
    backend = NetLampBackend(**kwargs)  # type: ignore[arg-type]
    return LampBoard(serial, backend), backend


async def test_a_board_is_tracked_from_its_making_to_its_closing() -> None:
    board, _ = lamp()
    assert board in lifetime.open_boards()
    await board.close()
    assert board not in lifetime.open_boards()


async def test_rescue_logs_one_line_per_board_and_keeps_boards_open(
    caplog: pytest.LogCaptureFixture,
) -> None:
    one, one_backend = lamp("ONE")
    two, _ = lamp("TWO")
    with caplog.at_level(logging.WARNING, logger="j5aio.lifetime"):
        rescued = lifetime.make_all_safe_now("a test asked")
    assert set(rescued) == {one, two}
    assert one_backend.states[0] is False
    assert one_backend.safe_now_threads == [threading.current_thread()]
    lines = [r.getMessage() for r in caplog.records]
    assert len(lines) == 2
    assert all("safety net when a test asked" in line for line in lines)
    assert one in lifetime.open_boards() and not one_backend.closed_now


async def test_boards_made_safe_in_order_are_made_safe_again_silently(
    caplog: pytest.LogCaptureFixture,
) -> None:
    board, backend = lamp()
    await board.setup()
    await LampBoard.make_all_safe()
    backend.states[0] = True
    with caplog.at_level(logging.WARNING, logger="j5aio.lifetime"):
        assert lifetime.make_all_safe_now("exit") == []
    assert backend.states[0] is False
    assert caplog.records == []
    await board.close()


async def test_closing_forgets_the_board_and_releases_its_port() -> None:
    board, backend = lamp()
    await board.setup()
    lifetime.make_all_safe_now("exit", close=True)
    assert backend.closed_now
    assert board not in lifetime.open_boards()
    assert board not in LampBoard.BOARDS
    await board.close()  # already closed: nothing more happens
    assert not backend.closed


async def test_a_failing_board_is_logged_and_the_others_still_made_safe(
    caplog: pytest.LogCaptureFixture,
) -> None:
    _, bad = lamp("BAD", fails=True)
    _, good = lamp("GOOD")
    with caplog.at_level(logging.ERROR, logger="j5aio.lifetime"):
        lifetime.make_all_safe_now("exit")
    assert good.states[0] is False
    assert bad.safe_now_threads
    assert "Could not make Lamp Board - BAD safe when exit" in caplog.text


def test_the_budget_bounds_the_whole(caplog: pytest.LogCaptureFixture) -> None:
    lamp("SLOW", delay=0.2)
    _, last = lamp("LAST")
    started = time.monotonic()
    with caplog.at_level(logging.ERROR, logger="j5aio.lifetime"):
        lifetime.make_all_safe_now("exit", budget=0.1)
    assert time.monotonic() - started < 1
    assert last.safe_now_threads == []
    assert "No time left to make Lamp Board - LAST safe" in caplog.text


async def test_from_another_thread_it_runs_in_the_boards_loop() -> None:
    _, backend = lamp()
    loop_thread = threading.current_thread()
    rescued = await anyio.to_thread.run_sync(lifetime.make_all_safe_now, "a watchdog")
    assert len(rescued) == 1
    assert backend.safe_now_threads == [loop_thread]


def test_a_loop_that_does_not_answer_is_bypassed() -> None:
    loop = asyncio.new_event_loop()
    made: list[NetLampBackend] = []

    async def make() -> None:
        made.append(lamp()[1])

    thread = threading.Thread(target=loop.run_forever, daemon=True)
    thread.start()
    try:
        asyncio.run_coroutine_threadsafe(make(), loop).result(2)
        loop.call_soon_threadsafe(time.sleep, 2.0)  # the loop is stuck
        time.sleep(0.05)
        started = time.monotonic()
        assert len(lifetime.make_all_safe_now("a watchdog", budget=0.2)) == 1
        assert time.monotonic() - started < 1.5  # far less than the 2 s the loop is stuck
        assert made[0].safe_now_threads == [threading.current_thread()]
    finally:
        loop.call_soon_threadsafe(loop.stop)
        thread.join(2)
        loop.close()


def test_the_end_of_a_loop_rescues_and_closes_its_boards(caplog: pytest.LogCaptureFixture) -> None:
    made: list[NetLampBackend] = []

    async def main() -> None:
        made.append(lamp()[1])

    with caplog.at_level(logging.WARNING, logger="j5aio.lifetime"):
        asyncio.run(main())
    assert made[0].states[0] is False
    assert made[0].closed_now
    assert "when its event loop finished" in caplog.text


def test_finishing_runs_the_exit_steps_then_the_net_once(monkeypatch: pytest.MonkeyPatch) -> None:
    steps: list[str] = []
    monkeypatch.setattr(hooks, "_exit_steps", [])
    monkeypatch.setattr(hooks, "_finished", False)
    _, backend = lamp()

    def step() -> None:
        steps.append("step")
        assert backend.safe_now_threads == []

    def broken() -> None:
        raise RuntimeError("a broken step")

    lifetime.add_exit_step(step)
    lifetime.add_exit_step(step)  # once only
    lifetime.add_exit_step(broken)
    hooks._at_exit()
    hooks._at_exit()
    assert steps == ["step"]
    assert backend.closed_now


def test_ctrl_c_ending_the_program_prints_one_line(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    # (the autouse fixture gives the suite its Ctrl-C back afterwards)
    reasons: list[str] = []
    previous: list[type[BaseException]] = []
    monkeypatch.setattr(hooks, "_finish", reasons.append)
    monkeypatch.setattr(hooks, "_previous_excepthook", lambda k, v, t: previous.append(k))
    monkeypatch.delattr(sys, "ps1", raising=False)
    hooks._excepthook(KeyboardInterrupt, KeyboardInterrupt(), None)
    assert capsys.readouterr().err == "Stopped (Ctrl-C); every board was made safe.\n"
    # the program is ending: a further Ctrl-C must not tear its exit hooks
    assert signal.getsignal(signal.SIGINT) is hooks._ignore_interrupt
    hooks._excepthook(RuntimeError, RuntimeError("bug"), None)
    assert previous == [RuntimeError]
    assert reasons[:2] == [
        "the program was stopped with Ctrl-C",
        "the program stopped on an unhandled RuntimeError",
    ]
    monkeypatch.setattr(rescue, "_failures", 1)
    hooks._excepthook(KeyboardInterrupt, KeyboardInterrupt(), None)
    assert "some boards could not be made safe" in capsys.readouterr().err
    logging.getLogger("j5aio").setLevel(logging.DEBUG)
    try:
        hooks._excepthook(KeyboardInterrupt, KeyboardInterrupt(), None)
    finally:
        logging.getLogger("j5aio").setLevel(logging.NOTSET)
    assert previous == [RuntimeError, KeyboardInterrupt]  # the full traceback, when debugging


def test_an_interactive_session_is_not_stopped(monkeypatch: pytest.MonkeyPatch) -> None:
    reasons: list[str] = []
    monkeypatch.setattr(hooks, "_finish", reasons.append)
    monkeypatch.setattr(hooks, "_previous_excepthook", lambda k, v, t: None)
    monkeypatch.setattr(sys, "ps1", ">>> ", raising=False)
    hooks._excepthook(KeyboardInterrupt, KeyboardInterrupt(), None)
    assert reasons == []


def test_ctrl_c_is_ignored_while_stopping() -> None:
    before = signal.getsignal(signal.SIGINT)
    term = signal.signal(signal.SIGTERM, hooks._on_terminate)
    try:
        with lifetime.quiet_interrupts():
            signal.raise_signal(signal.SIGINT)  # would raise KeyboardInterrupt otherwise
            signal.raise_signal(signal.SIGTERM)  # would raise SystemExit otherwise
        assert signal.getsignal(signal.SIGINT) is before
        assert signal.getsignal(signal.SIGTERM) is hooks._on_terminate
    finally:
        signal.signal(signal.SIGTERM, term)

    outcome: list[bool] = []

    def elsewhere() -> None:
        with lifetime.quiet_interrupts():
            outcome.append(signal.getsignal(signal.SIGINT) is before)

    thread = threading.Thread(target=elsewhere)
    thread.start()
    thread.join()
    assert outcome == [True]


def test_a_terminating_signal_exits_unless_a_robot_asked_for_it() -> None:
    with pytest.raises(SystemExit) as stopped:
        hooks._on_terminate(signal.SIGTERM, None)
    assert stopped.value.code == 128 + signal.SIGTERM

    got: list[int] = []

    async def main() -> None:
        remove = lifetime.on_terminate(asyncio.get_running_loop(), got.append)
        closed = asyncio.new_event_loop()
        closed.close()
        remove_closed = lifetime.on_terminate(closed, got.append)
        hooks._on_terminate(signal.SIGHUP, None)  # the closed loop is passed over
        await asyncio.sleep(0.01)
        remove_closed()
        remove()
        remove()  # twice is harmless

    asyncio.run(main())
    assert got == [signal.SIGHUP]


def test_a_terminating_signal_stops_a_running_loop_between_callbacks() -> None:
    steps: list[str] = []

    async def main() -> None:
        hooks._on_terminate(signal.SIGTERM, None)  # as if it arrived mid-step
        steps.append("the step finished")  # nothing was torn
        await asyncio.sleep(5)
        steps.append("never")

    with pytest.raises(SystemExit) as stopped:
        asyncio.run(main())
    assert stopped.value.code == 128 + signal.SIGTERM
    assert steps == ["the step finished"]


def test_a_second_terminating_signal_raises_at_once(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(hooks, "_terminating", True)

    async def main() -> None:
        hooks._on_terminate(signal.SIGHUP, None)

    with pytest.raises(SystemExit) as stopped:
        asyncio.run(main())
    assert stopped.value.code == 128 + signal.SIGHUP


def test_install_is_idempotent() -> None:
    lifetime.install()
    hook = sys.excepthook
    lifetime.install()
    assert sys.excepthook is hook


def test_the_default_backend_has_nothing_to_send() -> None:
    backend = LampBackend()
    assert backend.make_safe_now(0.1) is False
    backend.close_now()  # nothing to release


def test_a_board_whose_backend_is_no_backend_is_passed_over(
    caplog: pytest.LogCaptureFixture,
) -> None:
    # e.g. a test's stand-in, or a board whose constructor refused its backend after the
    # board was tracked: it drives nothing, so the net neither fails nor counts a failure.
    LampBoard("STANDIN", object())  # type: ignore[arg-type]
    _, good = lamp("GOOD")
    with caplog.at_level(logging.WARNING, logger="j5aio.lifetime"):
        rescued = lifetime.make_all_safe_now("exit")
    assert [board.serial_number for board in rescued] == ["GOOD"]
    assert good.states[0] is False
    assert "STANDIN" not in caplog.text
    assert rescue._failures == 0


def test_a_program_ending_during_game_over_waits_for_it_without_a_traceback(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    previous: list[type[BaseException]] = []
    reasons: list[str] = []
    monkeypatch.setattr(hooks, "_previous_excepthook", lambda k, v, t: previous.append(k))
    monkeypatch.setattr(hooks, "_finish", reasons.append)
    assert not lifetime.wait_for_game_over()  # no match has ended: nothing to wait for
    waited: list[float] = []
    monkeypatch.setattr(registry._game_over_done, "wait", waited.append)
    lifetime.begin_game_over()
    assert lifetime.game_over_begun()
    hooks._excepthook(RuntimeError, RuntimeError("the board has been closed"), None)
    assert previous == [] and reasons == [] and capsys.readouterr().err == ""
    assert waited == [lifetime.GAME_OVER_WAIT]


def test_the_exit_hook_during_game_over_waits_for_it_first(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setattr(hooks, "_exit_steps", [])
    monkeypatch.setattr(hooks, "_finished", False)
    order: list[str] = []
    monkeypatch.setattr(registry._game_over_done, "wait", lambda t: order.append("waited"))
    lifetime.add_exit_step(lambda: order.append("step"))
    lifetime.begin_game_over()
    hooks._at_exit()
    assert order == ["waited", "step"]


def test_a_board_made_after_game_over_is_refused_and_its_port_closed() -> None:
    lifetime.begin_game_over()
    backend = NetLampBackend()
    with pytest.raises(GameOverError, match="after game over"):
        LampBoard("L", backend)
    assert backend.closed_now and lifetime.open_boards() == []


async def test_making_a_board_installs_no_process_hooks_a_group_does(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    from j5aio.boards.board_group import BoardGroup

    from .conftest import LampBackend

    installs: list[str] = []
    monkeypatch.setattr(hooks, "install", lambda: installs.append("install"))
    board, _ = lamp()
    assert board in lifetime.open_boards() and installs == []  # a test's board: nothing
    group = await BoardGroup.get_board_group(LampBoard, LampBackend)
    assert installs == ["install"]  # a program's way to its boards installs the hooks
    for found in group:
        await found.close()

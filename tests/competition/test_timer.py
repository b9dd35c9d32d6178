"""Tests of the match timer in process (the process-ending path is replaced)."""

from __future__ import annotations

import logging
import sys
import threading
import time
from collections.abc import AsyncIterator

import anyio
import pytest

from j5aio import lifetime
from j5aio.boards.board import Board
from j5aio.boards.sr.v4 import MotorBoard
from j5aio.competition import timer as timer_module
from j5aio.competition.timer import MatchTimer, add_game_over_hook
from j5aio.simulator import kit as kit_module
from j5aio.simulator.environment import SIMULATED_ENVIRONMENT
from j5aio.simulator.kit import KitConfig, use_kit
from j5aio.simulator.sr_motor_fw3 import MotorMode


@pytest.fixture(autouse=True)
async def _fresh(monkeypatch: pytest.MonkeyPatch) -> AsyncIterator[None]:
    saved = kit_module._current
    interval = sys.getswitchinterval()
    monkeypatch.setattr(timer_module, "_hooks", [])
    for board in lifetime.open_boards():  # boards other tests left: not this test's kit
        lifetime.untrack(board)
    yield
    sys.setswitchinterval(interval)
    for board in list(Board.BOARDS):
        await board.close()
    for board in lifetime.open_boards():
        board.close_now()
    kit_module._current = saved


def test_duration_must_be_positive() -> None:
    with pytest.raises(ValueError, match="more than 0"):
        MatchTimer(0)


def test_stop_before_the_end_is_no_game_over() -> None:
    ended: list[int] = []
    timer = MatchTimer(30, end_process=ended.append)
    assert timer.ends_at is None and timer.remaining() is None
    timer.start()
    remaining = timer.remaining()
    assert remaining is not None and 29 < remaining <= 30
    with pytest.raises(RuntimeError, match="started already"):
        timer.start()
    timer.stop()
    timer.join(5)
    assert ended == [] and timer.ended_at is None


async def test_game_over_brakes_cancels_runs_hooks_and_exits_0(
    caplog: pytest.LogCaptureFixture,
) -> None:
    caplog.set_level(logging.INFO)
    kit = use_kit(KitConfig(0, 1, 0, 0, 0))
    board = (await SIMULATED_ENVIRONMENT.get_board_group(MotorBoard)).singular()
    await board.motors[0].set_power(0.7)
    exited = threading.Event()
    codes: list[int] = []
    order: list[str] = []

    def end_process(code: int) -> None:
        codes.append(code)
        exited.set()

    def cancel() -> None:
        order.append("cancel")

    def hook() -> None:
        order.append("hook")
        assert kit.motor_boards[0].motors[0].mode is MotorMode.BRAKE

    def broken_hook() -> None:
        raise RuntimeError("broken")

    add_game_over_hook(hook)
    add_game_over_hook(hook)  # once only
    add_game_over_hook(broken_hook)
    timer = MatchTimer(0.15, cancel=cancel, end_process=end_process, grace=0.01)
    timer.start()
    # Busy, never awaiting: the watchdog must not need this loop.
    deadline = time.monotonic() + 5
    while not exited.is_set() and time.monotonic() < deadline:
        pass
    assert codes == [0]
    assert order == ["cancel", "hook"]
    assert kit.motor_boards[0].motors[0].mode is MotorMode.BRAKE
    assert board not in Board.BOARDS and board not in lifetime.open_boards()  # closed
    assert timer.ended_at is not None and timer.ends_at is not None
    assert timer.ended_at >= timer.ends_at
    assert "Game over" in caplog.text
    assert "A game-over hook failed" in caplog.text
    assert "safety net when" not in caplog.text  # game over's rescue is expected


class _Unclosable:
    """A backend whose port cannot be closed (a stand-in for a broken driver)."""

    def make_safe_now(self, timeout: float) -> bool:
        return True

    def close_now(self) -> None:
        raise OSError("stuck")


async def test_a_board_that_cannot_be_closed_does_not_stop_game_over(
    caplog: pytest.LogCaptureFixture,
) -> None:
    kit = use_kit(KitConfig(0, 1, 0, 0, 0))
    stuck = MotorBoard.__new__(MotorBoard)
    stuck._backend = _Unclosable()  # type: ignore[assignment]
    stuck._is_closed = False
    stuck._serial_number = "STUCK"
    lifetime.track(stuck)
    board = (await SIMULATED_ENVIRONMENT.get_board_group(MotorBoard)).singular()
    await board.motors[0].set_power(0.7)
    codes: list[int] = []
    timer = MatchTimer(0.01, end_process=codes.append, grace=0)
    timer.start()
    await anyio.to_thread.run_sync(timer.join, 5)
    assert codes == [0]
    assert kit.motor_boards[0].motors[0].mode is MotorMode.BRAKE
    assert "stuck" in caplog.text  # reported, and the next pass braked the motors
    lifetime.untrack(stuck)


def test_a_failing_cancel_does_not_stop_game_over() -> None:
    codes: list[int] = []

    def cancel() -> None:
        raise RuntimeError("loop closed")

    timer = MatchTimer(0.01, cancel=cancel, end_process=codes.append, grace=0)
    timer.start()
    timer.join(5)
    assert codes == [0]


async def test_cancelling_an_awaiting_robot_body() -> None:
    """With a responsive loop the cancel lands first: the body unwinds in order."""
    codes: list[int] = []
    with anyio.CancelScope() as scope:
        loop = __import__("asyncio").get_running_loop()
        timer = MatchTimer(
            0.05,
            cancel=lambda: loop.call_soon_threadsafe(scope.cancel),
            end_process=codes.append,
            grace=0,
        )
        timer.start()
        await anyio.sleep(10)
    assert scope.cancelled_caught
    await anyio.to_thread.run_sync(timer.join, 5)
    assert codes == [0]

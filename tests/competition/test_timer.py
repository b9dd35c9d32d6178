"""Tests of the match timer in process (the process-ending path is replaced)."""

from __future__ import annotations

import io
import json
import logging
import os
import subprocess
import sys
import threading
import time
from collections.abc import AsyncIterator
from pathlib import Path

import anyio
import pytest

from j5aio import lifetime
from j5aio.boards.board import Board
from j5aio.boards.sr.v4 import MotorBoard
from j5aio.competition import timer as timer_module
from j5aio.competition.timer import MatchTimer, add_game_over_hook
from j5aio.errors import GameOverError
from j5aio.simulator import kit as kit_module
from j5aio.simulator.environment import SIMULATED_ENVIRONMENT
from j5aio.simulator.kit import KitConfig, use_kit
from j5aio.simulator.sr_motor_fw3 import MotorMode
from j5aio.tracebacks import run_program


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
    timer._disarm()
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


def test_a_program_cannot_stop_the_match() -> None:
    assert not hasattr(MatchTimer, "stop")  # game over always comes


async def test_after_game_over_no_board_can_be_opened_to_drive_again() -> None:
    kit = use_kit(KitConfig(0, 1, 0, 0, 0))
    board = (await SIMULATED_ENVIRONMENT.get_board_group(MotorBoard)).singular()
    await board.motors[0].set_power(0.5)
    codes: list[int] = []
    timer = MatchTimer(0.01, end_process=codes.append, grace=0)
    timer.start()
    await anyio.to_thread.run_sync(timer.join, 5)
    assert codes == [0] and lifetime.game_over_begun()
    assert kit.motor_boards[0].motors[0].mode is MotorMode.BRAKE
    with pytest.raises(GameOverError, match="cannot be opened after game over"):
        await SIMULATED_ENVIRONMENT.get_board_group(MotorBoard)
    assert kit.motor_boards[0].motors[0].mode is MotorMode.BRAKE
    assert not lifetime.open_boards()


async def test_a_program_ending_in_game_over_waits_for_it(tmp_path: Path) -> None:
    program = tmp_path / "program.py"
    program.write_text("raise RuntimeError('the board has been closed')\n")
    lifetime.begin_game_over()
    lifetime.end_game_over()  # as if the timer had ended the process
    err = io.StringIO()
    assert run_program(program, stderr=err) == 0
    assert err.getvalue() == ""  # no traceback: the match ended, the program did not fail


_DRIVING_AT_THE_END = """
import anyio
from j5aio.competition import trigger_start
from j5aio.kit import KitRobot


async def main():
    async with KitRobot() as robot:
        trigger_start()
        await robot.wait_start()
        motor = robot.motor_boards[0].motors[0]
        while True:
            try:
                await motor.set_power(0.5)
            except anyio.get_cancelled_exc_class():
                pass  # keeps driving: the next set_power meets a closed board
            await anyio.sleep(0)


anyio.run(main)
"""

def test_a_program_driving_at_the_end_ends_with_game_over_and_status_0(tmp_path: Path) -> None:
    metadata = tmp_path / "metadata.json"
    metadata.write_text(
        json.dumps({"arena": "A", "zone": 1, "mode": "COMP", "duration": 0.5,
                    "marker_offset": 0})
    )
    env = dict(os.environ)
    env.update(
        J5AIO_ENV="sim",
        J5AIO_METADATA=str(metadata),
        J5AIO_START_FILE=str(tmp_path / "start"),
        J5AIO_MEDIA_ROOTS=str(tmp_path / "media"),
        PYTHONPATH=os.pathsep.join([str(Path(__file__).parents[2]), env.get("PYTHONPATH", "")]),
    )
    done = subprocess.run(
        [sys.executable, "-c", _DRIVING_AT_THE_END],
        capture_output=True, text=True, env=env, timeout=60, check=False,
    )
    assert done.returncode == 0, done.stderr
    assert "Game over" in done.stderr
    assert "Traceback" not in done.stderr

from __future__ import annotations

import asyncio
import logging

import pytest

from j5aio.boards.board import Board
from j5aio.safety import make_all_safe_uncancellably

from .conftest import LampBackend, LampBoard


class SlowBoard(LampBoard):
    async def make_safe(self) -> None:
        await asyncio.sleep(0.05)
        await super().make_safe()


async def test_cancelling_the_caller_does_not_stop_make_safe() -> None:
    board = SlowBoard("slow", LampBackend())
    await board.setup()
    task = asyncio.ensure_future(make_all_safe_uncancellably())
    await asyncio.sleep(0.01)
    task.cancel()
    await asyncio.sleep(0)
    task.cancel()  # a second, impatient cancellation
    with pytest.raises(asyncio.CancelledError):
        await task
    assert board.safe_calls == 1
    assert board.lamp_backend.states[0] is False


async def test_a_hanging_board_is_given_up_on(caplog: pytest.LogCaptureFixture) -> None:
    class Hanging(LampBoard):
        async def make_safe(self) -> None:
            await asyncio.sleep(10)

    await Hanging("h", LampBackend()).setup()
    with caplog.at_level(logging.ERROR):
        await make_all_safe_uncancellably(timeout=0.05)
    assert "gave up waiting" in caplog.text


async def test_unexpected_failure_is_logged(
    caplog: pytest.LogCaptureFixture, monkeypatch: pytest.MonkeyPatch,
) -> None:
    async def explode() -> list[BaseException]:
        raise RuntimeError("registry broken")

    monkeypatch.setattr(Board, "make_all_safe", staticmethod(explode))
    with caplog.at_level(logging.ERROR):
        await make_all_safe_uncancellably()
    assert "registry broken" in caplog.text

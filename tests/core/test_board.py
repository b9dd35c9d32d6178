from __future__ import annotations

import logging

import pytest

from j5aio.boards.board import Board

from .conftest import LampBackend, LampBoard


async def test_setup_runs_once_and_registers() -> None:
    board = LampBoard("A", LampBackend())
    assert board not in Board.BOARDS
    await board.setup()
    await board.setup()
    assert board.setup_calls == 1
    assert board in Board.BOARDS
    assert board.firmware_version == "1.0"
    assert board.backend is board.lamp_backend


async def test_close_unregisters_and_closes_backend_once() -> None:
    board = LampBoard("A", LampBackend())
    await board.setup()
    await board.close()
    await board.close()
    assert board not in Board.BOARDS
    assert board.lamp_backend.closed


async def test_make_all_safe_reaches_all_and_collects_failures(
    caplog: pytest.LogCaptureFixture,
) -> None:
    class Broken(LampBoard):
        async def make_safe(self) -> None:
            raise RuntimeError("wire fell out")

    good = LampBoard("good", LampBackend())
    bad = Broken("bad", LampBackend())
    await good.setup()
    await bad.setup()
    with caplog.at_level(logging.ERROR):
        failures = await Board.make_all_safe()
    assert good.safe_calls == 1
    assert [str(f) for f in failures] == ["wire fell out"]
    assert "Could not make Lamp Board - bad safe" in caplog.text

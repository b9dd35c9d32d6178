"""Project-wide test configuration."""

from __future__ import annotations

import os
import socket
from collections.abc import AsyncIterator, Iterator

import pytest

from j5aio.boards.board import Board
from j5aio.simulator import kit as kit_module


def _free_tcp_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as probe:
        probe.bind(("127.0.0.1", 0))
        port: int = probe.getsockname()[1]
        return port


# Each test session gets its own robot-lock port, so that test runs going on side by side
# on one machine (and a real robot program) do not take each other's lock. Subprocesses
# started by the tests inherit it.
os.environ["J5AIO_LOCK_PORT"] = str(_free_tcp_port())


@pytest.fixture(autouse=True)
def _forget_boards() -> Iterator[None]:
    """Start and end every test with no registered boards."""
    Board.BOARDS.clear()
    yield
    Board.BOARDS.clear()


@pytest.fixture
async def fresh_kit() -> AsyncIterator[None]:
    """Restore the current simulated kit, and close every board the test opened."""
    saved = kit_module._current
    yield
    for board in list(Board.BOARDS):
        await board.close()
    kit_module._current = saved

"""Project-wide test configuration."""

from __future__ import annotations

import os
import random
import socket
from collections.abc import AsyncIterator, Iterator

import pytest

from j5aio.boards.board import Board
from j5aio.robot import DEFAULT_LOCK_PORT
from j5aio.safety import registry
from j5aio.simulator import kit as kit_module


def _ephemeral_ports() -> range:
    """The ports the system hands out to outgoing connections (Linux's; else IANA's)."""
    try:
        with open("/proc/sys/net/ipv4/ip_local_port_range") as ranges:
            low, high = (int(field) for field in ranges.read().split())
    except (OSError, ValueError):
        low, high = 49152, 65535
    return range(low, high + 1)


def _free_lock_port() -> int:
    """A port free now and outside the ephemeral range.

    A port the system picked (``bind(("127.0.0.1", 0))``) comes from the ephemeral range,
    from which every outgoing connection of the test run (a web page's socket, an MQTT
    client) also takes its local port: one of them could take the lock port meanwhile, and
    a robot made afterwards would fail to lock.
    """
    ephemeral = _ephemeral_ports()
    rng = random.Random()
    for _ in range(200):
        port = rng.randrange(20000, 32000)
        if port in ephemeral or port == DEFAULT_LOCK_PORT:
            continue
        with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as probe:
            try:
                probe.bind(("127.0.0.1", port))
            except OSError:
                continue
        return port
    raise RuntimeError("no free TCP port outside the ephemeral range for the robot lock")


# Each test session gets its own robot-lock port, so that test runs going on side by side
# on one machine (and a real robot program) do not take each other's lock. Subprocesses
# started by the tests inherit it.
os.environ["J5AIO_LOCK_PORT"] = str(_free_lock_port())


@pytest.fixture(autouse=True)
def _forget_boards() -> Iterator[None]:
    """Start and end every test with no registered boards, and no match over."""
    Board.BOARDS.clear()
    yield
    Board.BOARDS.clear()
    registry._game_over.clear()
    registry._game_over_done.clear()


@pytest.fixture
async def fresh_kit() -> AsyncIterator[None]:
    """Restore the current simulated kit, and close every board the test opened."""
    saved = kit_module._current
    yield
    for board in list(Board.BOARDS):
        await board.close()
    kit_module._current = saved

"""Project-wide test configuration."""

from __future__ import annotations

import os
import random
import signal
import socket
import sys
import tempfile
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


def _worker_number() -> int:
    """This process's number among pytest-xdist's workers (``gw3`` is 3); 0 without xdist."""
    name = os.environ.get("PYTEST_XDIST_WORKER", "gw0")
    digits = name.removeprefix("gw")
    return int(digits) if digits.isdigit() else 0


#: The ports a test run picks its robot-lock port from: below every ephemeral range in use
#: (Linux's default starts at 32768) and above the well-known and registered ports.
LOCK_PORTS = range(20000, 32000)
#: How many ports each pytest-xdist worker owns, so that no two workers share a lock port.
PORTS_PER_WORKER = 250


def _free_lock_port() -> int:
    """A port free now, outside the ephemeral range, and owned by this worker alone.

    A port the system picked (``bind(("127.0.0.1", 0))``) comes from the ephemeral range,
    from which every outgoing connection of the test run (a web page's socket, an MQTT
    client) also takes its local port: one of them could take the lock port meanwhile, and
    a robot made afterwards would fail to lock. Under pytest-xdist each worker picks from
    its own slice of :data:`LOCK_PORTS`, so two workers never pick the same port.
    """
    ephemeral = _ephemeral_ports()
    slices = len(LOCK_PORTS) // PORTS_PER_WORKER
    first = LOCK_PORTS.start + (_worker_number() % slices) * PORTS_PER_WORKER
    rng = random.Random()
    for _ in range(200):
        port = rng.randrange(first, first + PORTS_PER_WORKER)
        if port in ephemeral or port == DEFAULT_LOCK_PORT:
            continue
        with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as probe:
            try:
                probe.bind(("127.0.0.1", port))
            except OSError:
                continue
        return port
    raise RuntimeError("no free TCP port outside the ephemeral range for the robot lock")


# Each test session (each pytest-xdist worker) gets its own robot-lock port, so that test
# runs going on side by side on one machine (and a real robot program) do not take each
# other's lock. Subprocesses started by the tests inherit it.
os.environ["J5AIO_LOCK_PORT"] = str(_free_lock_port())

# The programs the tests start remember the plugins' entry points in a cache folder of
# the session's own (many run with a path of their own, each remembered in its own
# file), not in the user's: a test run leaves nothing behind. Removed at the session's
# end; tests of the remembering itself set their own folder.
_CACHE_FOLDER = tempfile.TemporaryDirectory(prefix="j5aio-test-cache-")
os.environ["J5AIO_CACHE_DIR"] = _CACHE_FOLDER.name


def _ignore_in_this_process_only(signum: int, frame: object) -> None:
    """Ignore a signal here; unlike ``SIG_IGN``, a program started from here does not."""


#: Set for the pytest-xdist workers by a run that was started with hang-ups ignored.
IGNORE_HANGUPS = "J5AIO_TEST_RUN_IGNORES_HANGUPS"


def _children_start_with_default_signals() -> None:
    """Let the programs the tests start get the default SIGHUP and SIGINT, however we run.

    ``nohup`` starts the run with SIGHUP ignored, and a shell's ``&`` with SIGINT ignored;
    an ignored signal stays ignored in every program started from here, so a test that
    sends one to a robot program would wait for an ending that never comes. A handler of
    our own does the same here (nothing), and is reset to the default in a started
    program, as a handler is on ``exec``. The run itself goes on ignoring what it was told
    to ignore; its pytest-xdist workers, which start with the default, are told through
    the environment.
    """
    if sys.platform == "win32":  # pragma: no cover - POSIX signals
        return
    hangups = signal.getsignal(signal.SIGHUP)
    if hangups is signal.SIG_IGN or os.environ.get(IGNORE_HANGUPS) == "1":
        os.environ[IGNORE_HANGUPS] = "1"
        signal.signal(signal.SIGHUP, _ignore_in_this_process_only)
    if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
        signal.signal(signal.SIGINT, _ignore_in_this_process_only)


_children_start_with_default_signals()


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

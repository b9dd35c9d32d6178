"""A third-party board package (tests/thirdparty/blinken) found through its entry point.

The package is installed in tox's tests environment; elsewhere these tests are skipped.
"""

from __future__ import annotations

import importlib.metadata
import os
import subprocess
import sys
import textwrap
from collections.abc import AsyncIterator
from pathlib import Path

import pytest
import serial

from j5aio.backends.console import CONSOLE_ENVIRONMENT
from j5aio.backends.hardware import HARDWARE_ENVIRONMENT, attach
from j5aio.board_kinds import board_kinds, get_kit
from j5aio.boards.board import Board
from j5aio.simulator import SERIAL_SIMULATORS
from j5aio.simulator.environment import SIMULATED_ENVIRONMENT
from j5aio.simulator.serve import serve_on_pty

PACKAGE = Path(__file__).parent / "blinken"

installed = any(
    entry_point.name == "blinken"
    for entry_point in importlib.metadata.entry_points(group="j5aio.boards")
)
pytestmark = pytest.mark.skipif(
    not installed,
    reason=f"the example plugin j5aio-blinken is not installed (pip install -e {PACKAGE}; "
    "tox's tests environment installs it)",
)


@pytest.fixture(autouse=True)
async def _close_boards() -> AsyncIterator[None]:
    yield
    for board in list(Board.BOARDS):
        await board.close()


def python_m_j5aio(*args: str, cwd: Path | None = None) -> subprocess.CompletedProcess[str]:
    environment = {k: v for k, v in os.environ.items() if not k.startswith("J5AIO_")}
    return subprocess.run(
        [sys.executable, "-m", "j5aio", *args],
        capture_output=True, text=True, timeout=60, env=environment, check=False, cwd=cwd,
    )


def test_the_plugin_is_registered_with_every_part() -> None:
    from j5aio_blinken import (
        BlinkenBoard,
        BlinkenConsoleBackend,
        BlinkenHardwareBackend,
        BlinkenSimulator,
    )

    kind = next(kind for kind in board_kinds() if kind.name == "blinken-v1")
    assert kind.package == "j5aio-blinken"
    assert SERIAL_SIMULATORS["blinken"] is BlinkenSimulator
    assert HARDWARE_ENVIRONMENT.get_backend(BlinkenBoard) is BlinkenHardwareBackend
    assert CONSOLE_ENVIRONMENT.get_backend(BlinkenBoard) is BlinkenConsoleBackend
    simulated = SIMULATED_ENVIRONMENT.get_backend(BlinkenBoard)
    assert issubclass(simulated, BlinkenHardwareBackend)
    assert dict(get_kit("blinken").boards) == {"sr-power": 1, "blinken": 1}


def test_list_shows_the_plugins_kind_of_board() -> None:
    result = python_m_j5aio("list")
    assert "blinken-v1" in result.stdout, result.stderr
    assert "[j5aio-blinken]" in result.stdout


@pytest.mark.skipif(sys.platform == "win32", reason="pseudo-terminals exist on POSIX only")
def test_simulate_serves_the_plugins_board() -> None:
    process = subprocess.Popen(
        [sys.executable, "-m", "j5aio", "simulate", "blinken", "--serial", "BL7"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
    )
    try:
        assert process.stdout is not None
        path = process.stdout.readline().strip()
        with serial.Serial(path, 115200, timeout=5) as port:
            port.write(b"V\n")
            assert port.readline() == b"BLINKEN:1\n"
            port.write(b"L2 1\nL2?\n")
            assert port.readline() == b"OK\n"
            assert port.readline() == b"1\n"
    finally:
        process.terminate()
        _, errors = process.communicate(timeout=10)
    assert "Blinken board (four LEDs) (serial number BL7)" in errors


def test_run_sim_finds_the_plugins_board_in_its_kit(tmp_path: Path) -> None:
    (tmp_path / "robot.py").write_text(
        textwrap.dedent(
            """
            import anyio
            from j5aio.environments import get_default_environment
            from j5aio.kit import KitRobot
            from j5aio.simulator.kit import current_kit
            from j5aio_blinken import BlinkenBoard

            async def main():
                async with KitRobot() as robot:
                    group = await robot.environment.get_board_group(BlinkenBoard)
                    await group[0].leds[3].set_state(True)
                    simulator = current_kit().simulators("blinken")[0]
                    print("blinken", group[0].serial_number, simulator.leds)
                    print("power", robot.power_board.serial_number)

            anyio.run(main)
            """
        )
    )
    result = python_m_j5aio("run", "--sim", "--kit", "blinken", "robot.py", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "blinken SIMBL0 [False, False, False, True]" in result.stdout
    assert "power SIMPB0" in result.stdout


@pytest.mark.skipif(sys.platform == "win32", reason="pseudo-terminals exist on POSIX only")
async def test_attach_identifies_the_plugins_board_after_j5aios_own() -> None:
    from j5aio_blinken import BlinkenBoard, BlinkenSimulator

    simulator = BlinkenSimulator("BL1")
    with serve_on_pty(simulator, time_scale=0) as server:
        board = await attach(server.path, time_scale=0.05)
        assert isinstance(board, BlinkenBoard)
        assert board.firmware_version == "1"
        await board.leds[1].set_state(True)
        assert await board.leds[1].get_state() is True
        await board.close()

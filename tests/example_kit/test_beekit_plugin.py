"""beekit installed as a package finds its way into j5aio through its entry point.

``pip install -e tests/example_kit`` installs it (tox's tests environment does); without
it these tests are skipped, saying so.
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
from beekit.backend import BeeBackend
from beekit.boards import BeeBoard
from beekit.console import BeeConsoleBackend
from beekit.simulator import BeeSimulator

from j5aio.backends.console import CONSOLE_ENVIRONMENT
from j5aio.backends.hardware import HARDWARE_ENVIRONMENT, attach
from j5aio.board_kinds import board_kinds, get_kit
from j5aio.boards.board import Board
from j5aio.simulator import SERIAL_SIMULATORS
from j5aio.simulator.environment import SIMULATED_ENVIRONMENT
from j5aio.simulator.serve import serve_on_pty

PACKAGE = Path(__file__).parent



def _installed() -> bool:
    """Whether beekit's entry point is installed where ``python -m j5aio`` will see it.

    The kit's folder is on ``sys.path`` (conftest.py), so a ``beekit.egg-info`` that an
    earlier ``pip install -e`` left there would make the entry point visible to this
    process only: that is not an installation, so that folder is not searched.
    """
    elsewhere = [entry for entry in sys.path if Path(entry or ".").resolve() != PACKAGE.resolve()]
    return any(
        entry_point.name == "beekit" and entry_point.group == "j5aio.boards"
        for distribution in importlib.metadata.distributions(path=elsewhere)
        for entry_point in distribution.entry_points
    )


pytestmark = pytest.mark.skipif(
    not _installed(),
    reason=f"the example kit beekit is not installed (pip install -e {PACKAGE}; "
    "tox's tests environment installs it)",
)


@pytest.fixture(autouse=True)
async def _close_boards() -> AsyncIterator[None]:
    yield
    for board in list(Board.BOARDS):
        await board.close()


def python_m_j5aio(*args: str, cwd: Path | None = None) -> subprocess.CompletedProcess[str]:
    """Run ``python -m j5aio`` as a student would, without this run's J5AIO_ settings.

    (Only its robot lock port is kept, so that the program runs beside another robot.)
    """
    environment = {
        k: v for k, v in os.environ.items()
        if not k.startswith("J5AIO_") or k == "J5AIO_LOCK_PORT"
    }
    return subprocess.run(
        [sys.executable, "-m", "j5aio", *args],
        capture_output=True, text=True, timeout=60, env=environment, check=False, cwd=cwd,
    )


def test_the_entry_point_registers_every_part() -> None:
    kind = next(kind for kind in board_kinds() if kind.name == "bee-fw2")
    assert kind.package == "beekit"
    assert SERIAL_SIMULATORS["bee"] is BeeSimulator
    assert HARDWARE_ENVIRONMENT.get_backend(BeeBoard) is BeeBackend
    assert CONSOLE_ENVIRONMENT.get_backend(BeeBoard) is BeeConsoleBackend
    assert issubclass(SIMULATED_ENVIRONMENT.get_backend(BeeBoard), BeeBackend)
    assert dict(get_kit("bee").boards) == {"sr-power": 1, "bee": 1}


def test_a_start_that_uses_no_bee_board_imports_none_of_its_classes() -> None:
    # Every start loads the installed plugins' kinds; the kind names its board, backends
    # and simulators by import path, so a program on the default kit imports none of them.
    program = textwrap.dedent(
        """
        import os, sys
        os.environ["J5AIO_ENV"] = "sim"
        from j5aio.sync import KitRobot
        robot = KitRobot()
        print(*sorted(name for name in sys.modules if name.startswith("beekit")))
        """
    )
    environment = {
        k: v for k, v in os.environ.items()
        if not k.startswith("J5AIO_") or k in ("J5AIO_LOCK_PORT", "J5AIO_CACHE_DIR")
    }
    result = subprocess.run(
        [sys.executable, "-c", program],
        capture_output=True, text=True, timeout=60, env=environment, check=False,
    )
    assert result.returncode == 0, result.stderr
    assert "beekit.kinds" in result.stdout.split()  # the plugin was loaded...
    assert not {"beekit.boards", "beekit.backend", "beekit.simulator"} & set(result.stdout.split())


def test_list_shows_the_bee_board_and_its_package() -> None:
    result = python_m_j5aio("list")
    assert result.returncode == 0, result.stderr
    line = next((line for line in result.stdout.splitlines() if "bee-fw2" in line), None)
    assert line is not None, result.stdout
    assert "[beekit]" in line


@pytest.mark.skipif(sys.platform == "win32", reason="pseudo-terminals exist on POSIX only")
def test_simulate_serves_a_bee_board_by_its_cli_name() -> None:
    process = subprocess.Popen(
        [sys.executable, "-m", "j5aio", "simulate", "bee", "--serial", "BEE7"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
    )
    try:
        assert process.stdout is not None
        path = process.stdout.readline().strip()
        with serial.Serial(path, 57600, timeout=5) as port:
            port.write(b"?\n")
            assert port.readline() == b"BEE:2.1\n"
            port.write(b"M1 -40\nL1\nX\n")
            assert port.readline() == b"OK\n"
            assert port.readline() == b"OK\n"
            assert port.readline() == b"ERR unknown command X\n"
    finally:
        process.terminate()
        _, errors = process.communicate(timeout=10)
    assert "Bee Board (serial number BEE7)" in errors


def test_run_sim_finds_the_bee_board_in_its_kit(tmp_path: Path) -> None:
    (tmp_path / "robot.py").write_text(
        textwrap.dedent(
            """
            from beekit.sync import BeeBoard
            from j5aio.simulator.kit import current_kit
            from j5aio.sync import KitRobot

            robot = KitRobot()
            bee = robot.environment.get_board_group(BeeBoard).singular()
            bee.motors[1].power = -0.333
            bee.led.state = True
            simulator = current_kit().simulators("bee")[0]
            print("bee", bee.serial_number, simulator.motor_steps, simulator.led)
            print("power", robot.power_board.serial_number)
            """
        )
    )
    result = python_m_j5aio("run", "--sim", "--kit", "bee", "robot.py", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "bee SIMBEE0 [0, -33] True" in result.stdout
    assert "power SIMPB0" in result.stdout



@pytest.mark.skipif(sys.platform == "win32", reason="pseudo-terminals exist on POSIX only")
async def test_attach_identifies_a_board_that_answers_in_one_quick_round(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    from j5aio.backends.hardware import port_search

    async def full_round(*args: object, **kwargs: object) -> Board:
        raise AssertionError("every kind was tried in turn, with its full waits")

    monkeypatch.setattr(port_search, "identify_on_port", full_round)
    simulator = BeeSimulator("BEE1")
    with serve_on_pty(simulator) as server:  # (at full time scale: the board answers)
        board = await attach(server.path)
        assert isinstance(board, BeeBoard)
        assert board.firmware_version == "2.1"
        await board.close()


async def test_attach_asks_each_kind_in_turn_when_no_quick_answer_comes(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    from j5aio.backends.hardware import identify

    monkeypatch.setattr(identify, "QUICK_BUDGET", 0.0)  # too short for any board
    with serve_on_pty(BeeSimulator("BEE1"), time_scale=0) as server:
        board = await attach(server.path, time_scale=0.05)
        assert isinstance(board, BeeBoard)
        await board.close()


async def test_attach_asks_each_kind_in_turn_when_the_quick_answer_misleads(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    from j5aio.backends.hardware import identify
    from j5aio.backends.hardware.sb.arduino_2024 import SBArduino2024HardwareBackend

    async def misled(*args: object, **kwargs: object) -> type[SBArduino2024HardwareBackend]:
        return SBArduino2024HardwareBackend  # which will not recognise a Bee Board

    monkeypatch.setattr(identify, "_answering_kind", misled)
    with serve_on_pty(BeeSimulator("BEE1"), time_scale=0) as server:
        board = await attach(server.path, time_scale=0.05)
        assert isinstance(board, BeeBoard)
        await board.close()


async def test_attach_identifies_a_bee_board_after_j5aios_own_boards() -> None:
    simulator = BeeSimulator("BEE1")
    with serve_on_pty(simulator, time_scale=0) as server:
        board = await attach(server.path, time_scale=0.05)
        assert isinstance(board, BeeBoard)
        # j5aio's own kinds probed the port first (identify_order=200), and left it usable.
        assert simulator.commands.index(b"?") > 0
        assert board.firmware_version == "2.1"
        await board.led.set_state(True)
        assert await board.led.get_state() is True
        await board.close()


# --- a plugin's boards held by KitRobot like its own ------------------------------------


@pytest.mark.usefixtures("fresh_kit")
async def test_kit_robot_holds_a_plugin_s_boards_like_its_own() -> None:
    from j5aio.boards.sr.v4 import PowerBoard
    from j5aio.kit import KitRobot
    from j5aio.simulator.kit import use_kit

    kit = use_kit("bee", time_scale=0)
    async with KitRobot(environment=SIMULATED_ENVIRONMENT, boards={"bees": BeeBoard}) as robot:
        bees = robot.board_group(BeeBoard)
        assert vars(robot)["bees"] is bees  # robot.bees, for students
        assert [bee.serial_number for bee in bees] == ["SIMBEE0"]
        await bees[0].motors[0].set_power(0.5)
        assert kit.simulators("bee")[0].motor_steps[0] == 50  # type: ignore[attr-defined]
        assert robot.power_board.serial_number == "SIMPB0"
        with pytest.raises(KeyError, match=r"no group of 'PowerBoard'.*it holds: BeeBoard"):
            robot.board_group(PowerBoard)


@pytest.mark.parametrize(
    ("boards", "error", "message"),
    [
        ({"motor_boards": BeeBoard}, ValueError, "'motor_boards' is already the robot's own"),
        ({"board_group": BeeBoard}, ValueError, "already the robot's own"),
        ({"2bees": BeeBoard}, ValueError, "give an identifier"),
        ({"_bees": BeeBoard}, ValueError, "not starting with '_'"),
        ({"bees": BeeBackend}, TypeError, "'bees' must name a Board subclass"),
        ([BeeBoard], TypeError, "must map attribute names to board classes"),
    ],
)
def test_kit_robot_refuses_boards_it_cannot_hold(
    boards: object, error: type[Exception], message: str
) -> None:
    from j5aio.kit import KitRobot

    with pytest.raises(error, match=message):
        KitRobot(environment=SIMULATED_ENVIRONMENT, boards=boards)  # type: ignore[arg-type]


def test_the_sync_kit_robot_takes_the_kit_s_wrapper_class() -> None:
    program = textwrap.dedent("""
        import os
        os.environ["J5AIO_LOCK_PORT"] = "0"
        import beekit.sync
        from j5aio.simulator.kit import use_kit
        from j5aio.sync import KitRobot, get_environment

        use_kit("bee", time_scale=0)
        robot = KitRobot(environment=get_environment("sim"), boards={"bees": beekit.sync.BeeBoard})
        bees = robot.board_group(beekit.sync.BeeBoard)
        assert type(bees[0]) is beekit.sync.BeeBoard, type(bees[0])
        bees[0].led.state = True
        print("held", bees[0].serial_number, bees[0].led.state)
    """)
    # this run's own robot lock port is kept, so that the robot runs beside another one
    environment = {
        k: v for k, v in os.environ.items()
        if not k.startswith("J5AIO_") or k == "J5AIO_LOCK_PORT"
    }
    result = subprocess.run(
        [sys.executable, "-c", program], capture_output=True, text=True, timeout=60,
        env=environment, check=False,
    )
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "held SIMBEE0 True"

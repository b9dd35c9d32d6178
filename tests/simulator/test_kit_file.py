"""Tests of kit files: the simulated kit described as the team's own robot."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from j5aio.board_kinds import KitDefinition
from j5aio.kit import KitRobot
from j5aio.simulator import kit as kit_module
from j5aio.simulator.environment import SIMULATED_ENVIRONMENT
from j5aio.simulator.kit import current_kit, use_kit
from j5aio.simulator.kit_file import (
    KIT_FILE_VARIABLE,
    kit_file_from_environment,
    load_kit_file,
    parse_kit,
    time_scale_of,
    wiring_from_environment,
)

ROOT = Path(__file__).resolve().parents[2]

TEAM_ROBOT = textwrap.dedent(
    """\
    # Our robot: two motor boards named by their serial numbers.
    based_on = "sr2023"
    time_scale = 0

    [[board]]
    simulator = "sr-motor-fw4"
    serial = "SR0UK1L"
    output = "H1"

    [[board]]
    simulator = "sr-motor-fw4"
    serial = "SR0AB12"
    output = "L3"

    [[board]]
    simulator = "sr-power-fw4"
    serial = "SRPB1X"
    """
)

TEAM_PROGRAM = textwrap.dedent(
    """\
    from j5aio.sync import KitRobot

    robot = KitRobot()
    robot.motor_boards["SR0UK1L"].motors[0].power = 0.5
    robot.motor_boards["SR0AB12"].motors[1].power = -0.25
    print("power board", robot.power_board.serial_number, flush=True)

    from j5aio.simulator.kit import current_kit

    kit = current_kit()
    print("drives", [m.power for b in kit.drive_motor_boards for m in b.motors], flush=True)
    """
)


@pytest.fixture
def robot_file(tmp_path: Path) -> Path:
    file = tmp_path / "robot.toml"
    file.write_text(TEAM_ROBOT)
    return file


def test_a_kit_file_gives_boards_serial_numbers_and_wiring(robot_file: Path) -> None:
    definition = load_kit_file(robot_file)
    assert definition.name == "robot"
    assert dict(definition.boards) == {
        "sr-power-fw4": 1, "sr-motor-fw4": 2, "sr-servo-fw4": 1, "sr-arduino-fw2": 1, "kch": 1,
    }
    assert definition.serials["sr-motor-fw4"] == ("SR0UK1L", "SR0AB12")
    assert definition.wiring["sr-motor-fw4"] == ("H1", "L3")
    assert definition.wiring["sr-servo-fw4"] == ("L0",)  # from sr2023
    assert time_scale_of(robot_file) == 0.0


async def test_a_program_naming_its_boards_by_serial_number_runs_on_it(
    robot_file: Path, fresh_kit: None
) -> None:
    kit = use_kit(load_kit_file(robot_file))
    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        assert robot.power_board.serial_number == "SRPB1X"
        await robot.motor_boards["SR0UK1L"].motors[0].set_power(0.5)
        assert kit.wiring is not None
        fed = {getattr(board, "serial_number", ""): out for board, out in kit.wiring.feeds}
        assert fed["SR0UK1L"] == 1 and fed["SR0AB12"] == 5
    use_kit(load_kit_file(robot_file))  # a fresh robot, its outputs off
    with pytest.warns(UserWarning, match="SR0AB12 .* output L3"):
        async with KitRobot(environment=SIMULATED_ENVIRONMENT, power_on=["H1", "L0"]) as robot:
            assert list(robot.motor_boards) == [robot.motor_boards["SR0UK1L"]]


def test_serials_may_be_left_to_the_simulator(tmp_path: Path) -> None:
    file = tmp_path / "two boards.toml"
    file.write_text(
        '[[board]]\nsimulator = "sr-motor"\n[[board]]\nsimulator = "sr-motor"\n'
        'serial = "MINE"\n'
    )
    definition = load_kit_file(file)
    assert definition.name == "two-boards"
    assert definition.serials["sr-motor"] == ("SIMMB0", "MINE")
    assert "sr-motor" not in definition.wiring  # the default wiring
    assert time_scale_of(file) is None


@pytest.mark.parametrize(
    ("text", "match"),
    [
        ("based_on = 3", "based_on is a kit's name"),
        ('based_on = "nokit"', "there is no kit called 'nokit'"),
        ("colour = 1", "unknown setting colour"),
        ("", "the kit would be empty"),
        ("board = 1", r"each board is a \[\[board\]\] table"),
        ('[[board]]\nsimulator = "sr-motor"\nwheels = 4', "board 1: unknown setting wheels"),
        ('[[board]]\nsimulator = "warp-drive"', "simulator 'warp-drive' does not exist"),
        (
            '[[board]]\nsimulator = "sr-motor"\noutput = "H0"\n[[board]]\nsimulator = "sr-motor"',
            "give every sr-motor board an output, or none",
        ),
        ('[[board]]\nsimulator = "sr-motor"\noutput = "L2"', "cannot be wired to L2"),
        ('[[board]]\nsimulator = "sr-motor"\noutput = "X9"', "no output 'X9'"),
        ('[[board]]\nsimulator = "sr-motor"\noutput = true', "give an output's name"),
        ("board = [", "not valid TOML"),
    ],
)
def test_a_bad_kit_file_says_what_is_wrong(tmp_path: Path, text: str, match: str) -> None:
    file = tmp_path / "bad.toml"
    file.write_text(text)
    with pytest.raises(ValueError, match=match) as raised:
        load_kit_file(file)
    assert str(file) in str(raised.value)


def test_a_bad_time_scale_is_refused(tmp_path: Path) -> None:
    file = tmp_path / "slow.toml"
    file.write_text('time_scale = -1\nbased_on = "sr2019"\n')
    with pytest.raises(ValueError, match="time_scale must be a number of 0 or more"):
        time_scale_of(file)


def test_the_same_kit_in_code() -> None:
    definition = parse_kit(
        {"board": [{"simulator": "sr-motor-fw4", "serial": "A1", "output": "H0"}]}, name="code"
    )
    assert isinstance(definition, KitDefinition)
    assert definition.serials == {"sr-motor-fw4": ("A1",)}


def test_the_environment_variable_chooses_the_kit(
    robot_file: Path, monkeypatch: pytest.MonkeyPatch, fresh_kit: None
) -> None:
    monkeypatch.delenv(KIT_FILE_VARIABLE, raising=False)
    assert kit_file_from_environment() is None
    assert wiring_from_environment() == {}
    monkeypatch.setenv(KIT_FILE_VARIABLE, str(robot_file))
    assert wiring_from_environment() == {"SR0UK1L": 1, "SR0AB12": 5}
    kit_module._current = None
    kit = current_kit()
    assert kit.wiring is not None  # wired from the start, as the robot is
    assert [getattr(b, "serial_number", None) for b in kit.drive_motor_boards] == [
        "SR0AB12", "SR0UK1L",
    ]
    monkeypatch.setenv(KIT_FILE_VARIABLE, str(robot_file.with_name("missing.toml")))
    with pytest.raises(ValueError, match=f"{KIT_FILE_VARIABLE}=.*missing.toml"):
        kit_file_from_environment()
    assert wiring_from_environment() == {}


def run_j5aio(*args: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT), env.get("PYTHONPATH", "")])
    for name in ("J5AIO_ENV", "J5AIO_KIT", KIT_FILE_VARIABLE):
        env.pop(name, None)
    return subprocess.run(
        [sys.executable, "-m", "j5aio", *args],
        capture_output=True, text=True, env=env, cwd=cwd, timeout=60, check=False,
    )


def test_run_kit_file_runs_the_team_program_unchanged(robot_file: Path, tmp_path: Path) -> None:
    program = tmp_path / "robot.py"
    program.write_text(TEAM_PROGRAM)
    result = run_j5aio("run", "--no-log", "--kit-file", str(robot_file), str(program), cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "power board SRPB1X" in result.stdout
    assert "drives [0.0, -0.25, 0.5, 0.0]" in result.stdout  # SR0AB12 sorts first


def test_run_refuses_a_bad_kit_file(tmp_path: Path, robot_file: Path) -> None:
    bad = tmp_path / "bad.toml"
    bad.write_text("colour = 1\n")
    program = tmp_path / "robot.py"
    program.write_text("")
    result = run_j5aio("run", "--kit-file", str(bad), str(program), cwd=tmp_path)
    assert result.returncode == 2
    assert "unknown setting colour" in result.stderr
    both = run_j5aio(
        "run", "--kit", "sr2019", "--kit-file", str(robot_file), str(program), cwd=tmp_path
    )
    assert both.returncode == 2
    assert "not allowed with argument" in both.stderr


def test_demo_kit_file_runs_the_demo_on_the_teams_robot(robot_file: Path, tmp_path: Path) -> None:
    result = run_j5aio("demo", "--kit-file", str(robot_file), "--seconds", "0.5", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "The kit: 'robot'" in result.stdout
    assert "SR0AB12 [" in result.stdout


def test_the_kit_looks_for_a_kit_file_by_the_same_variable() -> None:
    # (the kit reads the variable itself, so as not to import this reader without a file)
    from j5aio.simulator import kit

    assert kit._KIT_FILE_VARIABLE == KIT_FILE_VARIABLE

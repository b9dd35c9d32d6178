"""Tests of ``python -m j5aio run``'s match options, start and run log."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from j5aio.__main__ import main
from j5aio.competition.clock import TIME_SCALE_VARIABLE
from j5aio.competition.metadata import (
    MEDIA_ROOTS_VARIABLE,
    METADATA_VARIABLE,
    SBOT_METADATA_VARIABLE,
)
from j5aio.competition.runlog import LOG_DIR_VARIABLE
from j5aio.competition.start import START_FILE_VARIABLE
from j5aio.environments import ENVIRONMENT_VARIABLE
from j5aio.simulator import kit as kit_module

ROOT = Path(__file__).resolve().parents[2]

MATCH_PROGRAM = """
import anyio
from j5aio.kit import KitRobot

async def main():
    async with KitRobot() as robot:
        await robot.wait_start(timeout=20)
        print("started", robot.zone, robot.mode, robot.arena)
        motor = robot.motor_boards[0].motors[0]
        while True:
            try:
                await motor.set_power(0.5)
                await robot.sleep(0.05)
            except BaseException:
                pass

anyio.run(main)
"""


@pytest.fixture(autouse=True)
def _isolated(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    for name in (
        METADATA_VARIABLE, SBOT_METADATA_VARIABLE, TIME_SCALE_VARIABLE, LOG_DIR_VARIABLE,
        ENVIRONMENT_VARIABLE,
    ):
        monkeypatch.setenv(name, "")  # recorded, so that teardown restores it
        monkeypatch.delenv(name)
    monkeypatch.setenv(MEDIA_ROOTS_VARIABLE, str(tmp_path / "media"))
    monkeypatch.setenv(START_FILE_VARIABLE, str(tmp_path / "start"))
    monkeypatch.setattr(kit_module, "_current", kit_module._current)


def run_j5aio(folder: Path, program: str, *args: str) -> subprocess.CompletedProcess[str]:
    """Run ``python -m j5aio run ARGS robot.py`` in ``folder`` on ``program``'s text."""
    (folder / "robot.py").write_text(program)
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT), env.get("PYTHONPATH", "")])
    return subprocess.run(
        [sys.executable, "-m", "j5aio", "run", *args, "robot.py"],
        capture_output=True, text=True, timeout=60, env=env, cwd=folder, check=False,
    )


def test_a_simulated_match_from_the_command_line(tmp_path: Path) -> None:
    result = run_j5aio(
        tmp_path, MATCH_PROGRAM, "--sim", "--zone", "2", "--mode", "comp", "--arena", "B",
        "--duration", "1", "--start-after", "0.2", "--time-scale", "0.5",
    )
    assert result.returncode == 0, result.stderr
    assert "started 2 COMP B" in result.stdout
    assert "Game over" in result.stderr
    logs = list((tmp_path / "j5aio-logs").glob("run-*.log"))
    assert len(logs) == 1
    text = logs[0].read_text()
    assert "# metadata: mode COMP, arena B, zone 2, 1 s" in text
    assert "Kit: Student Robotics v4 Motor Board, serial SIMMB0, firmware 3" in text
    assert "started 2 COMP B" in text and "Game over" in text
    assert "it ends in 0.5 s" in text  # a 1 s match at half the real time per robot second


SR2023_PROGRAM = """
import anyio
from j5aio.boards.sr.v4 import MotorBoard, PowerBoard
from j5aio.environments import get_default_environment
from j5aio.robot import BaseRobot

class Robot(BaseRobot):
    async def setup(self):
        environment = get_default_environment()
        self.power_board = (await environment.get_board_group(PowerBoard)).singular()
        await self.power_board.outputs.power_on()  # the motor board's 12 V
        self.motor_boards = await environment.get_board_group(MotorBoard)

async def main():
    async with Robot() as robot:
        await robot.wait_start(timeout=20)
        print("started", robot.zone, type(robot.power_board).__name__)
        while True:
            try:
                await robot.motor_boards[0].motors[0].set_power(0.5)
                await robot.sleep(0.05)
            except BaseException:
                pass

anyio.run(main)
"""


def test_a_match_on_the_named_sr2023_kit(tmp_path: Path) -> None:
    result = run_j5aio(
        tmp_path, SR2023_PROGRAM, "--sim", "--kit", "sr2023", "--zone", "2", "--mode", "comp",
        "--duration", "0.5", "--start-after", "0.2",
    )
    assert result.returncode == 0, result.stderr
    assert "started 2 PowerBoardFw4" in result.stdout
    assert "Game over" in result.stderr
    (log,) = (tmp_path / "j5aio-logs").glob("run-*.log")
    assert "Kit: Student Robotics v4 Motor Board (firmware 4)" in log.read_text()


NEVER_WAITS_PROGRAM = """
import time
import anyio
from j5aio.kit import KitRobot

async def main():
    began = time.monotonic()
    async with KitRobot() as robot:  # no wait_start(): the start still starts the match
        motor = robot.motor_boards[0].motors[0]
        while True:
            try:
                await motor.set_power(0.5)
                await robot.sleep(0.05)
            except BaseException:
                pass
            if time.monotonic() - began > 20:
                print("ran on past the match")
                return

anyio.run(main)
"""


@pytest.mark.parametrize(
    ("metadata", "log_line"),
    [
        ({"zone": 1, "is_competition": True}, "zone 1, 150 s"),
        ({"zone": 3, "mode": "COMP", "game_timeout": 1}, "zone 3, 1 s"),
    ],
)
def test_a_match_program_that_never_waits_ends_with_the_match(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, metadata: dict[str, object], log_line: str
) -> None:
    path = tmp_path / "competition" / ("astoria.json" if "mode" in metadata else "metadata.json")
    path.parent.mkdir()
    path.write_text(json.dumps(metadata))
    args = ["--sim", "--start-after", "0.2"]
    if "is_competition" in metadata:
        args += ["--time-scale", "0.01"]  # sbot's 150 s match in 1.5 real seconds
    monkeypatch.setenv(SBOT_METADATA_VARIABLE, str(path.parent))
    result = run_j5aio(tmp_path, NEVER_WAITS_PROGRAM, *args)
    assert result.returncode == 0, result.stderr
    assert "Game over" in result.stderr and "ran on past the match" not in result.stdout
    (log,) = (tmp_path / "j5aio-logs").glob("run-*.log")
    assert log_line in log.read_text()


def test_a_bad_metadata_file_stops_before_the_program(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    bad = tmp_path / "metadata.json"
    bad.write_text(json.dumps({"mode": "COMP"}))
    monkeypatch.setenv(METADATA_VARIABLE, str(bad))
    program = tmp_path / "robot.py"
    program.write_text("raise SystemExit('must not run')")
    assert main(["run", "--sim", "--no-log", str(program)]) == 2
    assert "in COMP mode the file must say how long the match is" in capsys.readouterr().err


def test_dev_run_with_log_dir_and_options(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    program = tmp_path / "robot.py"
    program.write_text(
        "import os\nprint('scale', os.environ.get('J5AIO_TIME_SCALE'))\n"
        "from j5aio.competition import load_metadata\nprint('zone', load_metadata().zone)\n"
    )
    monkeypatch.setattr(sys, "argv", sys.argv[:])
    monkeypatch.setattr(sys, "path", sys.path[:])
    assert main(["run", "--sim", "--zone", "4", "--time-scale", "2", "--log-dir",
                 str(tmp_path / "logs"), "--start-after", "30", str(program)]) == 0
    assert kit_module.current_kit().time_scale == 2
    assert METADATA_VARIABLE not in os.environ  # the run's settings end with it
    assert TIME_SCALE_VARIABLE not in os.environ
    out = capsys.readouterr()
    assert "scale 2.0" in out.out and "zone 4" in out.out
    assert "logging this run to" in out.err
    (log,) = (tmp_path / "logs").glob("run-*.log")
    assert "zone 4" in log.read_text()


def test_an_unwritable_log_folder_is_reported_not_fatal(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    (tmp_path / "file").write_text("")
    program = tmp_path / "robot.py"
    program.write_text("print('ran')")
    monkeypatch.setattr(sys, "path", sys.path[:])
    assert main(["run", "--log-dir", str(tmp_path / "file" / "logs"), str(program)]) == 0
    out = capsys.readouterr()
    assert "ran" in out.out and "j5aio: no run log" in out.err


def test_range_messages(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    with pytest.raises(SystemExit):
        main(["run", "--duration", "4000", str(tmp_path / "robot.py")])
    assert "4000 s is out of range: give 0 < s <= 3600" in capsys.readouterr().err
    with pytest.raises(SystemExit):
        main(["run", "--time-scale", "-2", str(tmp_path / "robot.py")])
    assert "-2 is out of range: give 0 < F <= 1000" in capsys.readouterr().err


@pytest.mark.parametrize(
    "flags",
    [["--duration", "0"], ["--start-after", "-1"], ["--time-scale", "0"], ["--mode", "x"],
     ["--duration", "soon"]],
)
def test_bad_options_are_refused(flags: list[str], tmp_path: Path) -> None:
    with pytest.raises(SystemExit) as caught:
        main(["run", *flags, str(tmp_path / "robot.py")])
    assert caught.value.code == 2


def test_console_start_thread(monkeypatch: pytest.MonkeyPatch) -> None:
    import io

    from j5aio import __main__ as cli
    from j5aio.competition import start

    start.clear_trigger()
    monkeypatch.setattr(sys, "stdin", io.StringIO("\n"))
    cli._start_on_enter()
    assert start._take_trigger() == "trigger"
    start.clear_trigger()

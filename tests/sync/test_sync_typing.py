"""mypy --strict on code that uses the facade: precise types in, mistakes out."""

from __future__ import annotations

import os
import tempfile
import textwrap
import uuid
from pathlib import Path

import pytest
from mypy import api

from .sync_fakes import ROOT

GOOD = """
from j5aio.backends.console.sr.v4 import SRV4MotorBoardConsoleBackend, SRV4PowerBoardConsoleBackend
from j5aio.boards.sr.v4 import MotorBoard, PowerBoard
from j5aio.boards.sr.v4.power_board import PowerOutputPosition
from j5aio.components.motor import MotorSpecialState
from j5aio.sync import CONSOLE_ENVIRONMENT, BaseRobot, BoardGroup


class MyRobot(BaseRobot):
    def __init__(self) -> None:
        self.power_board = BoardGroup.get_board_group(
            PowerBoard, SRV4PowerBoardConsoleBackend,
        ).singular()
        self.motor_boards = BoardGroup.get_board_group(MotorBoard, SRV4MotorBoardConsoleBackend)


r = MyRobot()
reveal_type(r.power_board)
reveal_type(r.power_board.outputs[PowerOutputPosition.H0].is_enabled)
reveal_type(r.motor_boards[0].motors[1])
reveal_type(CONSOLE_ENVIRONMENT.get_board_group(MotorBoard))
r.motor_boards[0].motors[0].power = 0.5
r.motor_boards[0].motors[0].power = MotorSpecialState.BRAKE
r.power_board.piezo.buzz(0.25, 440)
for board in r.motor_boards:
    reveal_type(board)
from j5aio import sync
reveal_type(BoardGroup.get_board_group(sync.MotorBoard, SRV4MotorBoardConsoleBackend).singular())
reveal_type(CONSOLE_ENVIRONMENT.get_board_group(sync.PowerBoard))
"""

BAD = """
from j5aio.backends.console.sr.v4 import SRV4PowerBoardConsoleBackend
from j5aio.boards.sr.v4 import PowerBoard
from j5aio.boards.sr.v4.power_board import PowerOutputPosition
from j5aio.sync import BoardGroup

board = BoardGroup.get_board_group(PowerBoard, SRV4PowerBoardConsoleBackend).singular()
output = board.outputs[PowerOutputPosition.H0]
output.is_enabeld = True
output.is_enabled = "yes"
board.battery_sensor.voltage = 12.0
board.piezo.buzz("long", 440)
"""


@pytest.fixture(scope="module")
def mypy_report(tmp_path_factory: pytest.TempPathFactory) -> dict[str, list[str]]:
    folder = tmp_path_factory.mktemp("mypy_snippets")
    files = {}
    for name, source in (("good_snippet", GOOD), ("bad_snippet", BAD)):
        # a fresh module name, so that the shared cache never skips the snippet
        path = folder / f"{name}_{uuid.uuid4().hex}.py"
        path.write_text(textwrap.dedent(source), encoding="utf-8")
        files[name] = path
    # one cache per pytest-xdist worker: two mypy runs never share one
    worker = os.environ.get("PYTEST_XDIST_WORKER", "main")
    cache = Path(tempfile.gettempdir()) / f"j5aio-sync-typing-mypy-cache-{worker}"
    stdout, stderr, _status = api.run(
        [
            "--strict",
            "--no-error-summary",
            "--show-error-codes",
            "--cache-dir",
            str(cache),
            "--config-file",
            str(ROOT / "pyproject.toml"),
            *map(str, files.values()),
        ],
    )
    assert not stderr, stderr
    report: dict[str, list[str]] = {name: [] for name in files}
    for line in stdout.splitlines():
        for name, path in files.items():
            if line.startswith(str(path)):
                report[name].append(line[len(str(path)) + 1 :])
    return report


def test_facade_code_type_checks_with_precise_types(mypy_report: dict[str, list[str]]) -> None:
    lines = mypy_report["good_snippet"]
    errors = [line for line in lines if ": error:" in line]
    assert errors == []
    revealed = [line.split("Revealed type is ")[1] for line in lines if "Revealed type" in line]
    assert revealed == [
        '"j5aio.sync._generated.sr.PowerBoard"',
        '"bool"',
        '"j5aio.sync._generated.components.Motor"',
        '"j5aio.sync._generated.robot.BoardGroup[j5aio.sync._generated.sr.MotorBoard]"',
        '"j5aio.sync._generated.sr.MotorBoard"',
        '"j5aio.sync._generated.sr.MotorBoard"',
        '"j5aio.sync._generated.robot.BoardGroup[j5aio.sync._generated.sr.PowerBoard]"',
    ]


def test_mypy_rejects_misspellings_and_wrong_types(mypy_report: dict[str, list[str]]) -> None:
    errors = [line for line in mypy_report["bad_snippet"] if ": error:" in line]
    by_line = {int(line.split(":")[0]): line for line in errors}
    assert '"PowerOutput" has no attribute "is_enabeld"' in by_line[9]
    assert "[assignment]" in by_line[10]
    assert '"str"' in by_line[10]
    assert "voltage" in by_line[11]
    assert "[arg-type]" in by_line[12]
    assert len(errors) == 4

"""j5's three quick-start programs, with only their imports changed, on the console and on --sim.

They name the console backends, so they run on the console whichever environment is
chosen: ``run --sim`` must not get in their way. The second one ends by looking up a
motor board by the serial number ``218312``, which no console board has (each is
``SERIAL``, in j5 as here); it fails on that last line only, with a message listing the
boards that are there.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PROGRAMS = Path(__file__).resolve().parent / "j5_quickstart"

WAYS = {
    "console": [sys.executable],
    "sim": [sys.executable, "-m", "j5aio", "run", "--sim"],
}


def run(way: str, name: str, stdin: str = "") -> subprocess.CompletedProcess[str]:
    path = os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])
    return subprocess.run(
        [*WAYS[way], name], input=stdin, capture_output=True, text=True, timeout=60,
        cwd=PROGRAMS, env={**os.environ, "PYTHONPATH": path}, check=False,
    )


@pytest.mark.parametrize("way", WAYS)
def test_first_robot(way: str) -> None:
    result = run(way, "first_robot.py")
    assert result.returncode == 0, result.stderr
    assert result.stdout == ""


@pytest.mark.parametrize("way", WAYS)
def test_adding_boards(way: str) -> None:
    result = run(way, "adding_boards.py", "false\ntrue\n")
    lines = result.stdout.splitlines()
    assert lines[:2] == ["Found Power Board: SERIAL", "Power Board Firmware: None"]
    assert result.stdout.count("Start button state [true/false]") == 2
    assert "Found 1 Motor Board(s):" in lines
    assert " - SERIAL - Version None" in lines
    assert result.returncode == 1
    assert result.stderr.rstrip().splitlines()[-1 if way == "console" else -2] == (
        "KeyError: \"no MotorBoard with serial number '218312'; connected: SERIAL\""
    )


@pytest.mark.parametrize("way", WAYS)
def test_using_components(way: str) -> None:
    result = run(way, "using_components.py")
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    offs = [f"PowerBoard(SERIAL): Setting output {n} to False" for n in range(6)]
    assert lines[:7] == [*offs, "PowerBoard(SERIAL): Setting output 0 to True"]

"""Every sync example runs on the simulated kit with no input; the console one with its input."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from .sync_fakes import ROOT, child_env

EXAMPLES = ROOT / "examples"

SAFE_POWER_BOARD = [f"PowerBoard(SERIAL): Setting output {n} to False" for n in range(6)]


def run_example(
    name: str, stdin: str, **environ: str,
) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, str(EXAMPLES / name)],
        input=stdin,
        capture_output=True,
        text=True,
        timeout=30,
        env={**child_env(), **environ},
        cwd=ROOT,
        check=False,
    )


def test_every_sync_example_is_tested() -> None:
    tested = {"sync_blink_run_led.py", "sync_drive_forward.py", "sync_start_and_buzz.py",
              "sync_read_battery.py", "sync_any_kit.py", "sync_blink_and_drive.py",
              # run by tests/vision/test_locate_simulated.py (it needs the vision extra)
              "sync_drive_to_token.py"}
    assert {path.name for path in EXAMPLES.glob("sync_*.py")} == tested


# Runs an example on the simulated kit in a child Python, as ``run --sim`` does, then
# prints what the simulated boards themselves were left doing.
_ON_THE_KIT = """
import os, runpy, sys
os.environ["J5AIO_ENV"] = "sim"
from j5aio.simulator.kit import current_kit
kit = current_kit()
runpy.run_path(sys.argv[1], run_name="__main__")
print("KIT motors", [m.mode.name for m in kit.motor_boards[0].motors])
print("KIT run_led", kit.power_boards[0].run_led)
"""


def run_on_the_kit(name: str) -> tuple[list[str], list[str]]:
    """Run example ``name`` on the simulated kit with no input: (its lines, the kit's lines)."""
    result = subprocess.run(
        [sys.executable, "-c", _ON_THE_KIT, str(EXAMPLES / name)],
        stdin=subprocess.DEVNULL, capture_output=True, text=True, timeout=60,
        env=child_env(), cwd=ROOT, check=False,
    )
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    kit = [line for line in lines if line.startswith("KIT ")]
    return [line for line in lines if line not in kit], kit


@pytest.mark.parametrize("path", sorted(EXAMPLES.glob("sync_*.py")), ids=lambda p: p.name)
def test_every_sync_example_runs_under_run_sim_with_no_input(path: Path) -> None:
    result = subprocess.run(
        [sys.executable, "-m", "j5aio", "run", "--sim", str(path)],
        stdin=subprocess.DEVNULL, capture_output=True, text=True, timeout=60,
        env=child_env(), cwd=ROOT, check=False,
    )
    assert result.returncode == 0, result.stderr
    assert "ran out of input" not in result.stderr


def test_blink_run_led() -> None:
    out, kit = run_on_the_kit("sync_blink_run_led.py")
    assert out == ["The run LED is off."]
    assert "KIT run_led False" in kit


def test_drive_forward_then_stop() -> None:
    out, kit = run_on_the_kit("sync_drive_forward.py")
    assert out == ["Stopped: left is MotorSpecialState.BRAKE, right is MotorSpecialState.BRAKE."]
    assert "KIT motors ['BRAKE', 'BRAKE']" in kit


def test_start_and_buzz_starts_anyway_when_nobody_presses() -> None:
    out, _ = run_on_the_kit("sync_start_and_buzz.py")
    assert out == [
        "Press the start button to begin.",
        "Nobody pressed start within 3 s: starting anyway.",
        "Tune played.",
    ]


def test_blink_and_drive_zig_zags_with_the_pin_lit_on_the_straights() -> None:
    out, kit = run_on_the_kit("sync_blink_and_drive.py")
    assert out == ["Zig-zag done: both motors braked."]
    assert "KIT motors ['BRAKE', 'BRAKE']" in kit


def test_read_the_battery() -> None:
    out, _ = run_on_the_kit("sync_read_battery.py")
    # KitRobot switched the outputs on: the servo board's 12 servos, held centred, draw
    # 20 mA each (0.24 A) and pull the 12 V battery down by 0.24 A x 0.05 ohm.
    assert out == ["Battery: 11.99 V, drawing 0.24 A (2.9 W)."]


def test_the_j5_program_prints_what_j5_would() -> None:
    result = run_example("console_j5_program.py", "true\n")
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[0] == "Found Power Board: SERIAL"
    assert lines[1] == "Power Board Firmware: None"
    assert lines[2].endswith("PowerBoard(SERIAL): Set LED 0 to True")
    assert lines[3:5] == ["Found 1 Motor Board(s):", " - SERIAL - Version None"]
    assert lines[5:11] == SAFE_POWER_BOARD
    # j5's line, then the duty the board really drives (j5aio only).
    assert lines[11:14] == [
        "PowerBoard(SERIAL): Setting output 0 to True",
        "MotorBoard(SERIAL): Setting motor 0 to 0.5.",
        "MotorBoard(SERIAL): Motor 0: forward at 50% duty.",
    ]
    assert lines[14].startswith("PowerBoard(SERIAL): Buzzing at 440")
    assert lines[14].endswith("Hz for 250ms")
    assert lines[15:17] == [
        "MotorBoard(SERIAL): Setting motor 0 to BRAKE.",
        "MotorBoard(SERIAL): Setting motor 1 to BRAKE.",
    ]


def test_any_kit_on_the_console() -> None:
    result = run_example("sync_any_kit.py", "12.2\n", J5AIO_ENV="console")
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[0] == "Using the ConsoleEnvironment."
    assert "Battery: 12.2 V" in result.stdout
    assert "Motors: MotorSpecialState.BRAKE, MotorSpecialState.BRAKE" in lines


def test_any_kit_on_the_simulated_kit() -> None:
    result = run_example("sync_any_kit.py", "", J5AIO_ENV="sim")
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[0] == "Using the SimulatedEnvironment."
    assert lines[1].startswith("Battery: ")
    assert lines[2] == "Motors: MotorSpecialState.BRAKE, MotorSpecialState.BRAKE"

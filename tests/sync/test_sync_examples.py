"""Every sync example runs on the console boards with its input piped in."""

from __future__ import annotations

import subprocess
import sys

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
              "sync_read_battery.py", "sync_j5_compat.py", "sync_any_kit.py"}
    assert {path.name for path in EXAMPLES.glob("sync_*.py")} == tested


def test_blink_run_led() -> None:
    result = run_example("sync_blink_run_led.py", "")
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[:6] == ["PowerBoard(SERIAL): Set LED 0 to True",
                         "PowerBoard(SERIAL): Set LED 0 to False"] * 3
    assert lines[6] == "The run LED is off."
    assert lines[7:] == SAFE_POWER_BOARD


def test_drive_forward_then_stop() -> None:
    result = run_example("sync_drive_forward.py", "")
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[:6] == [
        "MotorBoard(SERIAL): Setting motor 0 to 0.6.",
        "MotorBoard(SERIAL): Motor 0: forward at 60% duty.",
        "MotorBoard(SERIAL): Setting motor 1 to 0.6.",
        "MotorBoard(SERIAL): Motor 1: forward at 60% duty.",
        "MotorBoard(SERIAL): Setting motor 0 to BRAKE.",
        "MotorBoard(SERIAL): Setting motor 1 to BRAKE.",
    ]
    assert lines[6] == "Stopped: left is MotorSpecialState.BRAKE, right is MotorSpecialState.BRAKE."


def test_wait_for_start_then_buzz() -> None:
    result = run_example("sync_start_and_buzz.py", "false\nfalse\ntrue\n")
    assert result.returncode == 0, result.stderr
    out = result.stdout
    assert out.count("Start button state [true/false]") == 3
    assert out.index("Started!") > out.rindex("Start button state")
    buzzes = [line for line in out.splitlines() if "Buzzing" in line]
    assert len(buzzes) == 3
    assert all(line.endswith("for 200ms") for line in buzzes)


def test_read_the_battery() -> None:
    result = run_example("sync_read_battery.py", "10.5\n2\n")
    assert result.returncode == 0, result.stderr
    assert "Battery: 10.50 V, drawing 2.00 A (21.0 W)." in result.stdout
    assert "The battery is low: charge it soon!" in result.stdout
    healthy = run_example("sync_read_battery.py", "12.5\n1\n")
    assert "Battery: 12.50 V, drawing 1.00 A (12.5 W)." in healthy.stdout
    assert "low" not in healthy.stdout


def test_the_j5_program_prints_what_j5_would() -> None:
    result = run_example("sync_j5_compat.py", "true\n")
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

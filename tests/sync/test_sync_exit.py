"""How a sync program ends: boards made safe and ports closed, whatever stops it."""

from __future__ import annotations

import signal
import subprocess
import time
from pathlib import Path

import pytest

from .sync_fakes import start_script, wait_for_line

PRELUDE = """
from j5aio.sync import BaseRobot, BoardGroup
from j5aio.backends.console.sr.v4 import SRV4MotorBoardConsoleBackend, SRV4PowerBoardConsoleBackend
from j5aio.boards.sr.v4 import MotorBoard, PowerBoard
from j5aio.boards.sr.v4.power_board import PowerOutputPosition


class ClosingMotorBackend(SRV4MotorBoardConsoleBackend):
    async def close(self) -> None:
        print("motor board port closed")


class MyRobot(BaseRobot):
    def __init__(self) -> None:
        self.power_board = BoardGroup.get_board_group(
            PowerBoard, SRV4PowerBoardConsoleBackend,
        ).singular()
        self.motor_board = BoardGroup.get_board_group(MotorBoard, ClosingMotorBackend).singular()


r = MyRobot()
r.motor_board.motors[0].power = 0.5
r.power_board.outputs[PowerOutputPosition.H0].is_enabled = True
"""

MADE_SAFE = [
    "MotorBoard(SERIAL): Setting motor 0 to BRAKE.",
    "MotorBoard(SERIAL): Setting motor 1 to BRAKE.",
    "PowerBoard(SERIAL): Setting output 0 to False",
    "motor board port closed",
]


def assert_made_safe_after_driving(output: str) -> None:
    driving = output.index("MotorBoard(SERIAL): Setting motor 0 to 0.5.\n")
    for line in MADE_SAFE:
        assert line + "\n" in output[driving:], f"{line!r} missing from {output!r}"


#: A liveness bound, not a speed goal: a program that hung on a board's timeout or a thread
#: join would take far longer; a loaded machine starting Python under coverage takes seconds.
PROMPTLY = 6.0


def run_to_end(
    source: str, tmp_path: Path, stdin: str = "",
) -> tuple[subprocess.Popen[str], str, str, float]:
    started = time.monotonic()
    process = start_script(source, tmp_path)
    out, err = process.communicate(stdin, timeout=20)
    return process, out, err, time.monotonic() - started


def test_program_that_closes_nothing_exits_promptly_with_boards_safe(tmp_path: Path) -> None:
    process, out, err, elapsed = run_to_end(PRELUDE + "print('end of program')\n", tmp_path)
    assert process.returncode == 0, err
    assert elapsed < PROMPTLY
    assert_made_safe_after_driving(out)
    assert out.index("end of program") < out.index(MADE_SAFE[0])


def test_uncaught_exception_still_makes_boards_safe(tmp_path: Path) -> None:
    source = PRELUDE + "raise RuntimeError('student bug')\n"
    process, out, err, elapsed = run_to_end(source, tmp_path)
    assert process.returncode == 1
    assert "RuntimeError: student bug" in err
    assert elapsed < PROMPTLY
    assert_made_safe_after_driving(out)


# 0 s: the signal lands while the call is handed over or its first prompt is read; 0.3 s:
# in the wait. (The race where the signal's wake-up ended the exit's wait for the boards
# early is pinned down by test_sync_runtime's shutdown test.)
@pytest.mark.parametrize("delay", [0.0, 0.3])
def test_sigterm_during_a_blocking_call_makes_boards_safe(tmp_path: Path, delay: float) -> None:
    source = PRELUDE + (
        "print('waiting for start', flush=True)\n"
        "r.power_board.wait_for_start_flash()\n"
        "print('started')\n"
    )
    process = start_script(source, tmp_path)
    try:
        before = wait_for_line(process, "waiting for start")
        time.sleep(delay)
        process.send_signal(signal.SIGTERM)
        out, err = process.communicate(timeout=5)
    finally:
        process.kill()
    assert process.returncode == 128 + signal.SIGTERM
    output = "\n".join(before) + "\n" + out
    assert "started" not in output.splitlines()
    assert_made_safe_after_driving(output)
    assert "Terminated by SIGTERM" in err
    assert "Traceback" not in err


SLOW_MOTOR = """
import anyio
from j5aio.sync import BoardGroup
from j5aio.backends.console.sr.v4 import SRV4MotorBoardConsoleBackend
from j5aio.boards.sr.v4 import MotorBoard


class SlowMotorBackend(SRV4MotorBoardConsoleBackend):
    async def set_motor_state(self, identifier, power):
        if power == 0.5:
            print("slow command sent", flush=True)
            await anyio.sleep(10)
        await super().set_motor_state(identifier, power)


board = BoardGroup.get_board_group(MotorBoard, SlowMotorBackend).singular()
board.motors[0].power = 0.25
board.motors[0].power = 0.5
print("motor command returned")
"""


def test_ctrl_c_during_a_motor_command_cancels_it_and_brakes(tmp_path: Path) -> None:
    process = start_script(SLOW_MOTOR, tmp_path)
    try:
        before = wait_for_line(process, "slow command sent")
        started = time.monotonic()
        process.send_signal(signal.SIGINT)
        out, err = process.communicate(timeout=5)
        elapsed = time.monotonic() - started
    finally:
        process.kill()
    lines = before + out.splitlines()
    assert err == "Stopped (Ctrl-C); every board was made safe.\n"
    assert process.returncode in (-signal.SIGINT, 128 + signal.SIGINT, 1)
    assert elapsed < PROMPTLY
    assert "motor command returned" not in lines
    assert "MotorBoard(SERIAL): Setting motor 0 to 0.5." not in lines
    assert lines[-2:] == [
        "MotorBoard(SERIAL): Setting motor 0 to BRAKE.",
        "MotorBoard(SERIAL): Setting motor 1 to BRAKE.",
    ]


BUSY_SIMULATED = """
from j5aio.boards.sr.v4 import MotorBoard, PowerBoard
from j5aio.sync import get_default_environment

environment = get_default_environment()
environment.get_board_group(PowerBoard)[0].outputs.power_on()  # the motor boards' 12 V
motor = environment.get_board_group(MotorBoard)[0].motors[0]
motor.power = 0.5
print("busy", flush=True)
while True:
    motor.power = 0.5
"""


def test_ctrl_c_twice_in_a_busy_program_prints_one_line(tmp_path: Path) -> None:
    # As `timeout -s INT` and some terminals do: the second one lands while stopping.
    env_source = "import os\nos.environ['J5AIO_ENV'] = 'sim'\n" + BUSY_SIMULATED
    process = start_script(env_source, tmp_path)
    try:
        wait_for_line(process, "busy")
        process.send_signal(signal.SIGINT)
        time.sleep(0.001)
        process.send_signal(signal.SIGINT)
        _, err = process.communicate(timeout=10)
    finally:
        process.kill()
    assert err == "Stopped (Ctrl-C); every board was made safe.\n"

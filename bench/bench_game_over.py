"""How soon the motors are braked after a match ends, whatever the program does.

Each trial starts a child Python on the simulated kit in COMP mode with a short match.
The child starts at once, sets a motor going and then tries hard to survive game over:

- ``swallow``: an async loop that drives the motor and swallows ``BaseException``;
- ``sync``: the sync facade, ``motor.power = 0.5`` and ``time.sleep`` in a tight loop
  that swallows ``BaseException``;
- ``blocking``: an async task that blocks the event loop in ``time.sleep``;
- ``spin``: a tight synchronous ``while True`` loop in async code;
- ``sr2023``: ``swallow`` on the SR 2023 kit (firmware 4 boards, text protocol).

The child's motor simulators record the time of every change of state; "braked within"
is the time from the scheduled end of the match to the moment every motor of the kit is
braked or coasting for good, on the machine's monotonic clock. A game-over hook prints
the record before the process ends. Run::

    python bench/bench_game_over.py [--trials 20]

Goal: braked within 50 ms of the match's end, exit status 0, in every trial.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from bench_signals import (  # type: ignore[import-not-found]
    GOAL_MS,
    ROOT,
    SAFE,
    braked_after,
)

__all__ = ["GOAL_MS", "PROGRAMS", "Trial", "braked_after", "report", "run_trial", "run_trials"]
#: The match's length in the trials, in seconds.
DURATION = 0.6

RECORDER = """
import json, time
from j5aio.competition import add_game_over_hook
from j5aio.simulator import sr_motor_fw3, sr_motor_fw4

_history = []


def _modes(sim):
    return [m.mode.name if hasattr(m, "mode") else m.drive.name for m in sim.motors]


def _record(cls):
    original = cls.receive

    def recording(self, data):
        before = _modes(self)
        reply = original(self, data)
        after = _modes(self)
        if after != before:
            _history.append((time.monotonic(), self.serial_number, after))
        return reply

    cls.receive = recording


_record(sr_motor_fw3.SRMotorBoardFw3Simulator)
_record(sr_motor_fw4.SRMotorBoardFw4Simulator)
_robot = []


def _dump():
    timer = _robot[0].match_timer if _robot else None
    end = timer.ends_at if timer is not None else None
    print("HISTORY " + json.dumps({"end": end, "history": _history}), flush=True)


add_game_over_hook(_dump)
"""

PROGRAMS = {
    "swallow": RECORDER
    + """
import anyio
from j5aio.competition import trigger_start
from j5aio.kit import KitRobot


async def main():
    async with KitRobot() as robot:
        _robot.append(robot)
        trigger_start()
        await robot.wait_start()
        motor = robot.motor_boards[0].motors[0]
        while True:
            try:
                await motor.set_power(0.5)
                await anyio.sleep(0)
            except BaseException:
                pass


anyio.run(main)
""",
    "sync": RECORDER
    + """
import time
from j5aio.boards.sr.v4 import MotorBoard, PowerBoard
from j5aio.competition import trigger_start
from j5aio.sync import BaseRobot, get_default_environment

robot = BaseRobot()
_robot.append(robot._core)
environment = get_default_environment()
environment.get_board_group(PowerBoard)[0].outputs.power_on()  # the motor boards' 12 V
motor = environment.get_board_group(MotorBoard)[0].motors[0]
trigger_start()
robot.wait_start()
while True:
    try:
        motor.power = 0.5
        time.sleep(0.001)
    except BaseException:
        pass
""",
    "blocking": RECORDER
    + """
import time
import anyio
from j5aio.competition import trigger_start
from j5aio.kit import KitRobot


async def block():
    time.sleep(3600)


async def main():
    async with KitRobot() as robot:
        _robot.append(robot)
        trigger_start()
        await robot.wait_start()
        await robot.motor_boards[0].motors[0].set_power(0.5)
        async with anyio.create_task_group() as tasks:
            tasks.start_soon(block)


anyio.run(main)
""",
    "spin": RECORDER
    + """
import anyio
from j5aio.competition import trigger_start
from j5aio.kit import KitRobot


async def main():
    async with KitRobot() as robot:
        _robot.append(robot)
        trigger_start()
        await robot.wait_start()
        await robot.motor_boards[0].motors[1].set_power(-0.5)
        count = 0
        while True:
            try:
                count += 1
            except BaseException:
                pass


anyio.run(main)
""",
    "sr2023": RECORDER
    + """
import anyio
from j5aio.boards.sr.v4 import MotorBoard, PowerBoard
from j5aio.competition import trigger_start
from j5aio.environments import get_default_environment
from j5aio.robot import BaseRobot


class Robot(BaseRobot):
    async def setup(self):
        environment = get_default_environment()
        power_board = (await environment.get_board_group(PowerBoard))[0]
        await power_board.outputs.power_on()  # the motor board's 12 V
        self.motor_boards = await environment.get_board_group(MotorBoard)


async def main():
    async with Robot() as robot:
        _robot.append(robot)
        trigger_start()
        await robot.wait_start()
        motor = robot.motor_boards[0].motors[0]
        while True:
            try:
                await motor.set_power(0.5)
                await anyio.sleep(0)
            except BaseException:
                pass


anyio.run(main)
""",
}
#: The named simulated kit each kind of program runs on (the default kit otherwise).
KITS = {"sr2023": "sr2023"}


@dataclass(frozen=True)
class Trial:
    """The outcome of one trial."""

    kind: str
    braked_after: float | None  # seconds from the match's end; None: never all safe
    drove: bool  # a motor was driven during the match (the trial means something)
    returncode: int
    stderr: str


def run_trial(kind: str, *, duration: float = DURATION, timeout: float = 30.0) -> Trial:
    """Run one child through a match of ``duration`` seconds and measure."""
    with tempfile.TemporaryDirectory() as folder:
        metadata = Path(folder) / "metadata.json"
        metadata.write_text(
            json.dumps(
                {"arena": "A", "zone": 1, "mode": "COMP", "duration": duration,
                 "marker_offset": 0}
            )
        )
        env = dict(os.environ)
        env["J5AIO_ENV"] = "sim"
        env["J5AIO_KIT"] = KITS.get(kind, "")
        env["J5AIO_METADATA"] = str(metadata)
        env["J5AIO_START_FILE"] = str(Path(folder) / "start")
        env["J5AIO_MEDIA_ROOTS"] = str(Path(folder) / "media")
        env["PYTHONPATH"] = os.pathsep.join([str(ROOT), env.get("PYTHONPATH", "")])
        process = subprocess.run(
            [sys.executable, "-c", PROGRAMS[kind]],
            capture_output=True,
            text=True,
            env=env,
            timeout=timeout,
            check=False,
        )
    lines = [x for x in process.stdout.splitlines() if x.startswith("HISTORY ")]
    record = json.loads(lines[-1].removeprefix("HISTORY ")) if lines else {}
    history = record.get("history", [])
    end = record.get("end")
    drove = any(set(modes) - SAFE for _, _, modes in history)
    after = braked_after(history, end) if end is not None else None
    return Trial(kind, after, drove, process.returncode, process.stderr)


def run_trials(trials: int, kinds: list[str] | None = None) -> list[Trial]:
    """Run ``trials`` trials of each kind of program."""
    return [run_trial(kind) for _ in range(trials) for kind in kinds or list(PROGRAMS)]


def report(results: list[Trial]) -> None:
    """Print the figures per kind of program."""
    print(f"{'program':<9} {'trials':>6} {'median ms':>10} {'max ms':>8} {'within 50 ms':>13}")
    for kind in PROGRAMS:
        mine = [r for r in results if r.kind == kind]
        if not mine:
            continue
        times = [r.braked_after * 1000 for r in mine if r.braked_after is not None]
        within = sum(1 for t in times if t <= GOAL_MS)
        median = statistics.median(times) if times else float("nan")
        worst = max(times) if times else float("nan")
        print(f"{kind:<9} {len(mine):>6} {median:>10.1f} {worst:>8.1f} {within:>8}/{len(mine)}")
        never = len(mine) - len(times)
        if never:
            print(f"  {never} trial(s) ended with a motor still driving")
        print(f"  exit statuses: {sorted({r.returncode for r in mine})}")


def main() -> None:
    """Run the benchmark from the command line."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--trials", type=int, default=20, help="trials per kind of program")
    options = parser.parse_args()
    report(run_trials(options.trials))


if __name__ == "__main__":
    main()

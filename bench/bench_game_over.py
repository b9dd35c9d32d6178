"""How soon the motors are braked after a match ends, whatever the program does.

Each trial runs a program with ``python -m j5aio run`` on the simulated kit in a short
COMP match, so under the match supervisor (:mod:`j5aio.competition.supervisor`), as on
match day. The program starts at once, sets a motor going and then tries hard to survive
game over:

- ``swallow``: an async loop that drives the motor and swallows ``BaseException``;
- ``sync``: the sync facade, ``motor.power = 0.5`` and ``time.sleep`` in a tight loop
  that swallows ``BaseException``;
- ``blocking``: an async task that blocks the event loop in ``time.sleep``;
- ``spin``: a tight synchronous ``while True`` loop in async code;
- ``sr2023``: ``swallow`` on the SR 2023 kit (firmware 4 boards, text protocol);
- ``reopen``: the sync facade asking for its boards again after game over and driving
  them (``get_board_group`` in a loop), as a program that restarts itself would;
- ``gil``: C code that keeps the GIL (``sum(range(4 * 10**8))`` in a loop);
- ``switch``: ``sys.setswitchinterval(30)`` and a spin;
- ``disarm``: the program stops its match timer (the private ``_disarm``) and drives on;
- ``fork``: the program forks a child that outlives it.

When the program's own game over makes the boards safe, its motor simulators' record
(printed by a game-over hook) gives the time from the scheduled end of the match to the
moment every motor of the kit is braked or coasting for good, on the machine's monotonic
clock; a motor driven again after that moves that moment later. When the program cannot
(the GIL is held, the timer disarmed), the supervisor ends its process group and the
simulated kit ends with it: the braking time is the supervisor's, which it prints. "group
gone" is the time from the end to the supervisor's exit, which comes after the whole
process group (the forked child too) has been ended. Run::

    python bench/bench_game_over.py [--trials 20] [--kinds gil,fork]

Goal: braked within 50 ms of the match's end, the process group gone within 1 s, exit
status 0 with a "Game over" line, in every trial.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import socket
import statistics
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from bench_signals import (  # type: ignore[import-not-found]
    GOAL_MS,
    ROOT,
    SAFE,
    braked_after,
)

__all__ = [
    "GOAL_MS",
    "GROUP_GOAL_MS",
    "PROGRAMS",
    "Trial",
    "braked_after",
    "report",
    "run_trial",
    "run_trials",
]
#: The match's length in the trials, in seconds.
DURATION = 0.6
#: The goal for the program's whole process group to be gone, in ms after the end.
GROUP_GOAL_MS = 1000.0

RECORDER = """
import json, time
from j5aio.competition import add_game_over_hook
from j5aio.simulator import sr_motor_fw3, sr_motor_fw4

_history = []
_said_drove = []


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
            if not _said_drove and set(after) - {"BRAKE", "COAST"}:
                # said at once: a supervisor's kill leaves no record at the end
                _said_drove.append(True)
                print("DROVE", flush=True)
        return reply

    cls.receive = recording


_record(sr_motor_fw3.SRMotorBoardFw3Simulator)
_record(sr_motor_fw4.SRMotorBoardFw4Simulator)
_robot = []


def _started(robot):
    # The match has started: note the robot, and tell the bench when the match ends.
    _robot.append(robot)
    print(f"END {robot.match_timer.ends_at!r}", flush=True)


def _drove():
    print("DROVE", flush=True)


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
        trigger_start()
        await robot.wait_start()
        _started(robot)
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
environment = get_default_environment()
environment.get_board_group(PowerBoard)[0].outputs.power_on()  # the motor boards' 12 V
motor = environment.get_board_group(MotorBoard)[0].motors[0]
trigger_start()
robot.wait_start()
_started(robot._core)
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
        trigger_start()
        await robot.wait_start()
        _started(robot)
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
        trigger_start()
        await robot.wait_start()
        _started(robot)
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
        trigger_start()
        await robot.wait_start()
        _started(robot)
        motor = robot.motor_boards[0].motors[0]
        while True:
            try:
                await motor.set_power(0.5)
                await anyio.sleep(0)
            except BaseException:
                pass


anyio.run(main)
""",
    "reopen": RECORDER
    + """
import time
from j5aio.boards.sr.v4 import MotorBoard, PowerBoard
from j5aio.competition import trigger_start
from j5aio.sync import BaseRobot, get_default_environment

robot = BaseRobot()
environment = get_default_environment()
environment.get_board_group(PowerBoard)[0].outputs.power_on()  # the motor boards' 12 V
trigger_start()
robot.wait_start()
_started(robot._core)
while True:
    try:
        environment.get_board_group(PowerBoard)[0].outputs.power_on()
        environment.get_board_group(MotorBoard)[0].motors[0].power = 0.5
        time.sleep(0.001)
    except BaseException:
        pass
""",
    "gil": RECORDER
    + """
import anyio
from j5aio.competition import trigger_start
from j5aio.kit import KitRobot


async def main():
    async with KitRobot() as robot:
        trigger_start()
        await robot.wait_start()
        _started(robot)
        await robot.motor_boards[0].motors[0].set_power(0.5)
        _drove()
        while True:
            sum(range(4 * 10**8))  # C code that never lets go of the GIL


anyio.run(main)
""",
    "switch": RECORDER
    + """
import sys
import anyio
from j5aio.competition import trigger_start
from j5aio.kit import KitRobot


async def main():
    async with KitRobot() as robot:
        trigger_start()
        await robot.wait_start()
        _started(robot)
        await robot.motor_boards[0].motors[0].set_power(0.5)
        _drove()
        sys.setswitchinterval(30)
        while True:
            pass


anyio.run(main)
""",
    "disarm": RECORDER
    + """
import anyio
from j5aio.competition import trigger_start
from j5aio.kit import KitRobot


async def main():
    async with KitRobot() as robot:
        trigger_start()
        await robot.wait_start()
        _started(robot)
        robot.match_timer._disarm()
        motor = robot.motor_boards[0].motors[0]
        await motor.set_power(0.5)
        _drove()
        while True:
            await motor.set_power(0.5)
            await anyio.sleep(0.001)


anyio.run(main)
""",
    "fork": RECORDER
    + """
import os, time
import anyio
from j5aio.competition import trigger_start
from j5aio.kit import KitRobot


async def main():
    async with KitRobot() as robot:
        trigger_start()
        await robot.wait_start()
        _started(robot)
        motor = robot.motor_boards[0].motors[0]
        await motor.set_power(0.5)
        pid = os.fork()
        if pid == 0:
            while True:  # the forked child holds every port the program had
                time.sleep(0.01)
        print(f"FORKED {pid}", flush=True)
        while True:
            try:
                await motor.set_power(0.5)
                await anyio.sleep(0.001)
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
    group_gone_after: float | None = None  # seconds from the end to the supervisor's exit
    by_supervisor: bool = False  # the supervisor had to end the program
    forked_alive: bool = False  # a forked child was still running afterwards


_KILLED = re.compile(r"its processes were ended (\d+) ms after the end")


def _alive(pid: int) -> bool:
    """Whether process ``pid`` still runs (a zombie nobody reaps has ended)."""
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except OSError:
        try:
            os.kill(pid, 0)
        except OSError:
            return False
        return True
    return state not in ("Z", "X")


def _free_port() -> int:
    """A free TCP port for the child's robot lock (so no other robot program stops it)."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as probe:
        probe.bind(("127.0.0.1", 0))
        port: int = probe.getsockname()[1]
        return port


def run_trial(kind: str, *, duration: float = DURATION, timeout: float = 60.0) -> Trial:
    """Run one program through a match of ``duration`` seconds under ``j5aio run``."""
    with tempfile.TemporaryDirectory() as folder:
        metadata = Path(folder) / "metadata.json"
        metadata.write_text(
            json.dumps(
                {"arena": "A", "zone": 1, "mode": "COMP", "duration": duration,
                 "marker_offset": 0}
            )
        )
        program = Path(folder) / "robot.py"
        program.write_text(PROGRAMS[kind])
        env = dict(os.environ)
        env["J5AIO_ENV"] = "sim"
        env["J5AIO_KIT"] = KITS.get(kind, "")
        env["J5AIO_METADATA"] = str(metadata)
        env["J5AIO_START_FILE"] = str(Path(folder) / "start")
        env["J5AIO_MEDIA_ROOTS"] = str(Path(folder) / "media")
        env["J5AIO_LOCK_PORT"] = str(_free_port())
        env["PYTHONPATH"] = os.pathsep.join([str(ROOT), env.get("PYTHONPATH", "")])
        process = subprocess.run(
            [sys.executable, "-m", "j5aio", "run", "--no-log", str(program)],
            capture_output=True,
            text=True,
            env=env,
            timeout=timeout,
            check=False,
        )
        finished = time.monotonic()
    out = process.stdout.splitlines()
    lines = [x for x in out if x.startswith("HISTORY ")]
    record = json.loads(lines[-1].removeprefix("HISTORY ")) if lines else {}
    history = record.get("history", [])
    ends = [float(x.split()[1]) for x in out if x.startswith("END ")]
    end = record.get("end") or (ends[-1] if ends else None)
    drove = any(set(modes) - SAFE for _, _, modes in history) or "DROVE" in out
    killed = _KILLED.search(process.stderr)
    if killed is not None:
        after: float | None = int(killed.group(1)) / 1000  # the kit ended with the process
    else:
        after = braked_after(history, end) if end is not None else None
    forked = [int(x.split()[1]) for x in out if x.startswith("FORKED ")]
    return Trial(
        kind,
        after,
        drove,
        process.returncode,
        process.stderr,
        group_gone_after=finished - end if end is not None else None,
        by_supervisor=killed is not None,
        forked_alive=any(_alive(pid) for pid in forked),
    )


def run_trials(trials: int, kinds: list[str] | None = None) -> list[Trial]:
    """Run ``trials`` trials of each kind of program."""
    return [run_trial(kind) for _ in range(trials) for kind in kinds or list(PROGRAMS)]


def report(results: list[Trial]) -> None:
    """Print the figures per kind of program."""
    print(
        f"{'program':<9} {'trials':>6} {'median ms':>10} {'max ms':>8} {'within 50 ms':>13} "
        f"{'gone p50 ms':>12} {'gone max ms':>12} {'by supervisor':>14}"
    )
    for kind in PROGRAMS:
        mine = [r for r in results if r.kind == kind]
        if not mine:
            continue
        times = [r.braked_after * 1000 for r in mine if r.braked_after is not None]
        within = sum(1 for t in times if t <= GOAL_MS)
        median = statistics.median(times) if times else float("nan")
        worst = max(times) if times else float("nan")
        gone = [r.group_gone_after * 1000 for r in mine if r.group_gone_after is not None]
        gone_median = statistics.median(gone) if gone else float("nan")
        gone_worst = max(gone) if gone else float("nan")
        killed = sum(1 for r in mine if r.by_supervisor)
        print(
            f"{kind:<9} {len(mine):>6} {median:>10.1f} {worst:>8.1f} {within:>8}/{len(mine)} "
            f"{gone_median:>12.0f} {gone_worst:>12.0f} {killed:>10}/{len(mine)}"
        )
        never = len(mine) - len(times)
        if never:
            print(f"  {never} trial(s) ended with a motor still driving")
        late = sum(1 for t in gone if t > GROUP_GOAL_MS)
        if late:
            print(f"  {late} trial(s) with the process group alive after {GROUP_GOAL_MS:.0f} ms")
        if any(r.forked_alive for r in mine):
            print("  a forked child outlived the match")
        missing = sum(1 for r in mine if "Game over" not in r.stderr)
        if missing:
            print(f"  {missing} trial(s) without a Game over line")
        print(f"  exit statuses: {sorted({r.returncode for r in mine})}")
        failed = next((r for r in mine if r.returncode != 0), None)
        if failed is not None:
            last = (failed.stderr.strip().splitlines() or ["(nothing on stderr)"])[-1]
            print(f"  a failed trial's last line: {last}")


def main() -> None:
    """Run the benchmark from the command line."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--trials", type=int, default=20, help="trials per kind of program")
    parser.add_argument(
        "--kinds", default=",".join(PROGRAMS), help="which kinds of program, comma separated"
    )
    options = parser.parse_args()
    kinds = [kind for kind in options.kinds.split(",") if kind]
    unknown = sorted(set(kinds) - set(PROGRAMS))
    if unknown:
        parser.error(f"no kind of program called {', '.join(unknown)}; choose from "
                     f"{', '.join(PROGRAMS)}")
    report(run_trials(options.trials, kinds))


if __name__ == "__main__":
    main()

"""How soon the motors are braked after a signal stops a busy program.

Each trial starts a child Python on the simulated kit that drives a motor in a busy loop
(``motor.power = 0.5`` through the sync facade, or ``await motor.set_power(0.5)`` in an
async program with no robot), waits a random moment, then sends it SIGINT or SIGTERM.
The child's motor simulators record the time of every change of state; "braked within"
is the time from the signal to the moment every motor of the kit is braked or coasting
for good, measured on the machine's monotonic clock (shared by all processes on Linux).
Run::

    python bench/bench_signals.py [--trials 100]

Goal: braked within 50 ms of the signal in 100 of 100 trials.
"""

from __future__ import annotations

import argparse
import json
import os
import random
import signal
import statistics
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
GOAL_MS = 50.0
SAFE = {"BRAKE", "COAST"}

RECORDER = """
import atexit, json, time
from j5aio.simulator import sr_motor_fw3

_history = []
_receive = sr_motor_fw3.SRMotorBoardFw3Simulator.receive


def _recording_receive(self, data):
    before = self.motors
    reply = _receive(self, data)
    if self.motors != before:
        _history.append((time.monotonic(), self.serial_number, [m.mode.name for m in self.motors]))
    return reply


sr_motor_fw3.SRMotorBoardFw3Simulator.receive = _recording_receive
atexit.register(lambda: print("HISTORY " + json.dumps(_history), flush=True))
"""

PROGRAMS = {
    "sync": RECORDER
    + """
from j5aio.boards.sr.v4 import MotorBoard, PowerBoard
from j5aio.sync import get_default_environment

environment = get_default_environment()
environment.get_board_group(PowerBoard)[0].outputs.power_on()  # the motor boards' 12 V
motor = environment.get_board_group(MotorBoard)[0].motors[0]
motor.power = 0.5
print("ready", flush=True)
while True:
    motor.power = 0.5
""",
    "async": RECORDER
    + """
import anyio
from j5aio.boards.sr.v4 import MotorBoard, PowerBoard
from j5aio.environments import get_default_environment


async def main():
    environment = get_default_environment()
    await (await environment.get_board_group(PowerBoard))[0].outputs.power_on()
    motor = (await environment.get_board_group(MotorBoard))[0].motors[0]
    await motor.set_power(0.5)
    print("ready", flush=True)
    while True:
        await motor.set_power(0.5)


anyio.run(main)
""",
}


@dataclass(frozen=True)
class Trial:
    """The outcome of one trial."""

    kind: str
    signal_name: str
    braked_after: float | None  # seconds from the signal; None: never all safe
    returncode: int
    stderr: str


def braked_after(history: list[tuple[float, str, list[str]]], sent: float) -> float | None:
    """Seconds from ``sent`` until every board's motors were safe for good, or None."""
    latest: dict[str, list[str]] = {}
    safe_since: float | None = None
    for when, serial, modes in history:
        latest[serial] = modes
        all_safe = all(set(m) <= SAFE for m in latest.values())
        if all_safe and safe_since is None:
            safe_since = when
        elif not all_safe:
            safe_since = None
    if safe_since is None or not latest:
        return None
    return max(safe_since - sent, 0.0)


def run_trial(kind: str, signum: int, *, rng: random.Random) -> Trial:
    """Run one child, signal it while it is busy, and measure."""
    env = dict(os.environ)
    env["J5AIO_ENV"] = "sim"
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT), env.get("PYTHONPATH", "")])
    process = subprocess.Popen(
        [sys.executable, "-c", PROGRAMS[kind]],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=env,
    )
    try:
        assert process.stdout is not None
        line = process.stdout.readline()
        if line.strip() != "ready":
            process.kill()
            _, err = process.communicate(timeout=10)
            raise RuntimeError(f"the {kind} child did not start: {line!r} {err}")
        time.sleep(rng.uniform(0.005, 0.05))
        sent = time.monotonic()
        process.send_signal(signum)
        out, err = process.communicate(timeout=20)
    finally:
        process.kill()
    history_lines = [x for x in out.splitlines() if x.startswith("HISTORY ")]
    history = json.loads(history_lines[-1].removeprefix("HISTORY ")) if history_lines else []
    return Trial(
        kind,
        signal.Signals(signum).name,
        braked_after(history, sent),
        process.returncode,
        err,
    )


def run_trials(trials: int, *, seed: int = 1) -> list[Trial]:
    """Run ``trials`` trials of each kind, alternating SIGINT and SIGTERM."""
    rng = random.Random(seed)
    results = []
    for number in range(trials):
        signum = signal.SIGINT if number % 2 == 0 else signal.SIGTERM
        for kind in PROGRAMS:
            results.append(run_trial(kind, signum, rng=rng))
    return results


def report(results: list[Trial]) -> None:
    """Print the figures per kind of program."""
    print(f"{'program':<8} {'trials':>6} {'median ms':>10} {'max ms':>8} {'within 50 ms':>13}")
    for kind in PROGRAMS:
        mine = [r for r in results if r.kind == kind]
        times = [r.braked_after * 1000 for r in mine if r.braked_after is not None]
        within = sum(1 for t in times if t <= GOAL_MS)
        median = statistics.median(times) if times else float("nan")
        worst = max(times) if times else float("nan")
        print(f"{kind:<8} {len(mine):>6} {median:>10.1f} {worst:>8.1f} {within:>8}/{len(mine)}")
        never = len(mine) - len(times)
        if never:
            print(f"  {never} trial(s) ended with a motor still driving")
        codes = sorted({r.returncode for r in mine})
        print(f"  exit statuses: {codes}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--trials", type=int, default=100, help="trials per kind of program")
    parser.add_argument("--seed", type=int, default=1, help="seed of the random waits")
    options = parser.parse_args()
    report(run_trials(options.trials, seed=options.seed))


if __name__ == "__main__":
    main()

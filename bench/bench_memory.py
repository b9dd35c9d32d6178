"""Peak memory of a whole sync program on the simulated kit, against j5 0.12's console program.

Each case is a new child process that makes its robot, switches a power output and an
LED on, drives a motor at half power and stops it, then prints its peak resident set
size as its last act: ``VmHWM`` of ``/proc/self/status`` on Linux (``ru_maxrss`` would
report at least the peak of the bench process the child was forked from), else
``ru_maxrss``, with the number of Python threads then alive (each costs a stack's
touched pages and, in glibc, a malloc arena of its own). Cases:

* j5aio, sync: ``KitRobot()`` from ``j5aio.sync`` on the simulated kit (``J5AIO_ENV=sim``);
* j5aio, sync, every wrapper: the same program, then every wrapper class of the facade
  imported (as a program using every kind of board would): what loading only the
  wrappers a program uses saves;
* j5aio, async: the same program with ``async with KitRobot()``, for reference;
* the floor: the same interpreter after ``import asyncio`` and nothing else, what any
  asyncio program holds;
* the portal floor, for context: an anyio event loop running in a thread (a blocking
  portal, as the sync facade's runtime runs one) and nothing of j5aio;
* the anyio floor, for context: ``anyio.run`` of an empty coroutine (asyncio and anyio's
  asyncio backend, which every program on j5aio runs, sync or async), and nothing of
  j5aio: the figure above it is j5aio's own;
* j5 0.12 (its own venv, made by ``_peers.py``): the same steps on j5's console power and
  motor boards (the program of j5's quick start).

Rounds are interleaved and shuffled; the table shows medians in MiB and the ratio to j5.
Run (Linux and macOS)::

    python bench/bench_memory.py [--rounds 7] [--compare CHECKOUT] [--no-peer]

Goal: the sync program on the simulated kit peaks at most 3 MiB above the floor (the
median of ``import asyncio`` in the same run). The portal floor above the floor is what
the sync runtime's event loop thread costs before any board.
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _children import (  # type: ignore[import-not-found]
    J5_ROBOT,
    Case,
    j5_python,
    j5aio_env,
    print_table,
    run_interleaved,
    run_reporting,
)

#: The most the sync program may peak above the floor (import asyncio), MiB.
GOAL_ABOVE_FLOOR_MIB = 3.0
MARKER = "MAXRSS"

# The program's own peak: VmHWM, the high-water mark of the process's memory since it
# started this program. Not ru_maxrss on Linux: that keeps the peak of the process it was
# forked from (this bench, some 16 MiB) across exec, which hid any smaller program's peak.
REPORT = f"""
import sys
try:
    with open("/proc/self/status") as status:
        peak = next(int(line.split()[1]) * 1024 for line in status if line.startswith("VmHWM:"))
except (OSError, StopIteration):
    import resource
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    peak *= 1 if sys.platform == "darwin" else 1024
import threading
print({MARKER!r}, peak, threading.active_count(), flush=True)
"""

SYNC_STEPS = """\
from j5aio.sync import KitRobot

robot = KitRobot()
robot.power_board.outputs[0].is_enabled = True
robot.power_board.run_led.state = True
motor = robot.motor_boards[0].motors[0]
motor.power = 0.5
motor.power = 0
"""
SYNC_PROGRAM = SYNC_STEPS + REPORT
# The same, then every wrapper class of the facade loaded (not the environment constants,
# whose first use makes environments, nor the core classes of the wrappers).
EVERY_WRAPPER_PROGRAM = SYNC_STEPS + """\
import j5aio.sync
for name in j5aio.sync.__all__:
    if not name.isupper():
        getattr(j5aio.sync, name)
""" + REPORT

ASYNC_PROGRAM = """\
import anyio
from j5aio.kit import KitRobot

async def main() -> None:
    async with KitRobot() as robot:
        await robot.power_board.outputs[0].set_is_enabled(True)
        await robot.power_board.run_led.set_state(True)
        motor = robot.motor_boards[0].motors[0]
        await motor.set_power(0.5)
        await motor.set_power(0)

anyio.run(main)
""" + REPORT

# The floor: the interpreter and asyncio, what every asyncio program holds.
FLOOR_PROGRAM = """\
import asyncio
""" + REPORT

# For context: anyio's own share (its asyncio backend, loaded by anyio.run), no j5aio.
ANYIO_PROGRAM = """\
import anyio

async def main() -> None:
    pass

anyio.run(main)
""" + REPORT

# For context: anyio with an event loop running in a thread, as the sync facade runs one
# (a blocking portal), and no j5aio.
PORTAL_PROGRAM = """\
from anyio.from_thread import start_blocking_portal

with start_blocking_portal() as portal:
    portal.call(lambda: None)
""" + REPORT

J5_PROGRAM = J5_ROBOT + """\
from j5.boards.sr.v4.power_board import PowerOutputPosition

robot.power_board.outputs[PowerOutputPosition.H0].is_enabled = True
robot.power_board._run_led.state = True  # j5 0.12 keeps its LEDs private
motor = robot.motor_boards.singular().motors[0]
motor.power = 0.5
motor.power = 0
""" + REPORT


def _other_checkout(env: dict[str, str], checkout: str) -> dict[str, str]:
    """``env`` with another checkout of j5aio first on the path (``--compare``)."""
    return {**env, "PYTHONPATH": os.pathsep.join([checkout, env["PYTHONPATH"]])}


# ``python -c`` puts the working directory first on the path, before PYTHONPATH: run from
# a checkout, every case would import that checkout's j5aio, ``--compare``'s too. Safe-path
# mode (Python 3.11+) leaves it out, so PYTHONPATH alone says which j5aio a case runs.
SAFE_PATH = {"PYTHONSAFEPATH": "1"}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=7, help="runs of each case (default 7)")
    parser.add_argument(
        "--compare", metavar="CHECKOUT", default="",
        help="another checkout of j5aio (before a change, say): its async and sync cases "
        "run in the same interleaved rounds",
    )
    parser.add_argument(
        "--no-peer", action="store_true",
        help="leave j5 out (its robot lock is one port for the whole machine: two benches "
        "running j5 at once fail)",
    )
    options = parser.parse_args()

    sim = j5aio_env(J5AIO_ENV="sim", **SAFE_PATH)
    sync = Case("j5aio sync, simulated kit", [sys.executable, "-c", SYNC_PROGRAM], sim)
    every = Case(
        "j5aio sync, every wrapper", [sys.executable, "-c", EVERY_WRAPPER_PROGRAM], sim,
    )
    cases = [
        sync, every,
        Case("j5aio async, simulated kit", [sys.executable, "-c", ASYNC_PROGRAM], sim),
    ]
    if options.compare:
        cases += [
            Case(f"{case.name} ({options.compare})", case.argv,
                 _other_checkout(case.env, options.compare))
            for case in list(cases)
        ]
    floor = Case("floor: import asyncio", [sys.executable, "-c", FLOOR_PROGRAM], j5aio_env())
    portal = Case("portal, no j5aio", [sys.executable, "-c", PORTAL_PROGRAM], j5aio_env())
    anyio_floor = Case("anyio.run, no j5aio", [sys.executable, "-c", ANYIO_PROGRAM], j5aio_env())
    cases += [floor, portal, anyio_floor]
    peer = None if options.no_peer else j5_python()
    j5 = None
    if peer is not None:
        j5 = Case("j5 console program", [str(peer), "-c", J5_PROGRAM], j5aio_env())
        cases.append(j5)
    threads: dict[str, str] = {}

    def measure(case: Case) -> float:
        peak, alive = run_reporting(case, MARKER).split()
        threads[case.name] = alive
        return float(peak)

    run_interleaved(cases, options.rounds, measure)
    print(f"peak RSS at the end of the program, {options.rounds} interleaved rounds")
    print_table(
        "peak memory", cases, "MiB", reference=j5, scale=1 / 2**20,
        extra=lambda case: f"threads {threads[case.name]}",
    )
    mib = sync.median / 2**20
    limit = floor.median / 2**20 + GOAL_ABOVE_FLOOR_MIB
    above = (sync.median - floor.median) / 2**20
    print(
        f"\ngoal (sync program <= the floor + {GOAL_ABOVE_FLOOR_MIB:.0f} MiB = {limit:.1f} MiB): "
        f"{mib:.1f} MiB, floor + {above:.1f} MiB  {'met' if mib <= limit else 'NOT met'}"
    )
    portal_share = (portal.median - floor.median) / 2**20
    print(f"  of which the portal (an anyio loop in a thread, no j5aio): {portal_share:.1f} MiB")
    anyio_share = (anyio_floor.median - floor.median) / 2**20
    own = (sync.median - anyio_floor.median) / 2**20
    print(
        f"  of which anyio's asyncio backend (anyio.run, no j5aio): {anyio_share:.1f} MiB; "
        f"j5aio's own (above anyio.run): {own:.1f} MiB"
    )
    unused = (every.median - sync.median) / 2**20
    print(f"  the wrappers the program does not use, left unloaded: {unused:.2f} MiB")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

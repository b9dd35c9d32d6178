"""Whole process to a ready robot: from starting the interpreter to the robot having its boards.

Each case is a new child process; the time runs from just before the parent starts it to
the moment the parent reads the child's ``READY`` line (printed once the robot has found
its boards), so it holds the interpreter's start-up, the imports, finding the boards and
the hand-offs to the event loop. Cases:

* j5aio, async: ``async with KitRobot() as robot`` under ``anyio.run``, on the simulated
  kit (``J5AIO_ENV=sim``, as ``python -m j5aio run --sim`` sets it);
* j5aio, sync: ``robot = KitRobot()`` from ``j5aio.sync``, on the simulated kit;
* the floor: the same interpreter starting ``anyio.run`` on an empty coroutine (asyncio,
  anyio and this venv's site packages; no j5aio), what any asyncio program pays;
* j5 0.12 (its own venv, made by ``_peers.py``): the console robot of j5's quick start (a
  power board and the motor boards, on console backends).

Rounds are interleaved and shuffled; the table shows medians and the ratio to j5. Run::

    python bench/bench_startup.py [--rounds 15] [--kit NAME] [--compare CHECKOUT] [--imports]

``--imports`` also says, for each j5aio case and the floor, what its process has imported
once the robot is ready: how many modules (all of them, and j5aio's) and how many of
j5aio's classes are dataclasses (each costs a few hundred microseconds to make); and how
many garbage collections ran until then, and their time (every object an import or a
start makes counts towards the next collection, so the program pays for its
allocations there too).

Goal: a ready robot on the simulated kit, async and sync, at most 20 ms after the floor
(the median of ``anyio.run`` on an empty coroutine in the same run). The sync case's
figure above the async one is the sync runtime's share (its event loop thread, the
portal, the facade's wrappers).
"""

from __future__ import annotations

import argparse
import functools
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _children import (  # type: ignore[import-not-found]
    J5_ROBOT,
    Case,
    j5_python,
    j5aio_env,
    print_table,
    run_interleaved,
)

#: The most a ready robot may take above the floor (anyio.run, no j5aio), ms.
GOAL_ABOVE_FLOOR_MS = 20.0
MARKER = "READY"

ASYNC_PROGRAM = f"""\
import anyio
from j5aio.kit import KitRobot

async def main() -> None:
    async with KitRobot() as robot:
        print({MARKER!r}, len(robot.motor_boards), flush=True)

anyio.run(main)
"""

SYNC_PROGRAM = f"""\
from j5aio.sync import KitRobot

robot = KitRobot()
print({MARKER!r}, len(robot.motor_boards), flush=True)
"""

J5_PROGRAM = J5_ROBOT + f"print({MARKER!r}, len(robot.motor_boards), flush=True)\n"

# The floor under the async program: the interpreter (with this venv's site packages),
# asyncio and anyio starting and ending an event loop, and nothing of j5aio.
FLOOR_PROGRAM = f"""\
import anyio

async def main() -> None:
    print({MARKER!r}, 0, flush=True)

anyio.run(main)
"""


# Counts the garbage collections (and their time) from the program's first line on
# (--imports; the interpreter's own start is before it, and the same for every case).
_GC_WATCH = """\
import gc as _gc, time as _time
_gc_seen = [0, 0.0, 0.0]  # collections, their seconds, when the current one started
def _gc_watch(phase, info):
    if phase == "start":
        _gc_seen[2] = _time.perf_counter()
    else:
        _gc_seen[0] += 1
        _gc_seen[1] += _time.perf_counter() - _gc_seen[2]
_gc.callbacks.append(_gc_watch)
"""

# What a program has imported at its ready line, printed as one line (--imports).
_IMPORTS_REPORT = f"""\
import dataclasses as _dataclasses, sys as _sys
_ours = [_name for _name in list(_sys.modules) if _name.split(".")[0] == "j5aio"]
_classes = {{
    _value for _name in _ours for _value in list(vars(_sys.modules[_name]).values())
    if isinstance(_value, type) and _dataclasses.is_dataclass(_value)
    and _value.__module__.split(".")[0] == "j5aio"
}}
print(
    {MARKER!r}, "IMPORTS", len(_sys.modules), len(_ours), len(_classes), _gc_seen[0],
    _gc_seen[1], flush=True,
)
"""


def _reporting_imports(program: str) -> str:
    """``program`` printing what it has imported just before its ready line."""
    lines = program.splitlines(keepends=True)
    at = next(index for index, line in enumerate(lines) if f"print({MARKER!r}" in line)
    indent = lines[at][: len(lines[at]) - len(lines[at].lstrip())]
    report = "".join(f"{indent}{line}" for line in _IMPORTS_REPORT.splitlines(keepends=True))
    return "".join([_GC_WATCH, *lines[:at], report, *lines[at:]])


def imports_at_ready(case: Case, folder: str) -> tuple[int, int, int, int, float]:
    """What ``case``'s program has at its ready line: modules (all, j5aio's), j5aio
    dataclasses, and the garbage collections run so far (how many, and their seconds)."""
    program = _reporting_imports(case.argv[-1])
    done = subprocess.run(
        [*case.argv[:-1], program], env=case.env, capture_output=True, text=True, cwd=folder,
        timeout=120, check=False,
    )
    for line in done.stdout.splitlines():
        if line.startswith(f"{MARKER} IMPORTS "):
            fields = line.split()[2:]
            modules, ours, dataclasses, collections = map(int, fields[:4])
            return modules, ours, dataclasses, collections, float(fields[4])
    raise RuntimeError(f"{case.name}: no imports line:\n{done.stderr[-2000:]}")


def paired_above(case: Case, floor: Case) -> tuple[float, float, float]:
    """The first quartile, median and third quartile of ``case`` minus ``floor``, round by round.

    Each round runs every case once, so the two values of a round met the same machine.
    """
    differences = [value - base for value, base in zip(case.values, floor.values, strict=True)]
    if len(differences) < 2:
        return differences[0], differences[0], differences[0]
    low, middle, high = statistics.quantiles(differences, n=4)  # (middle: the median)
    return low, middle, high


def time_to_ready(case: Case, folder: str) -> float:
    """Seconds from starting ``case``'s process to reading its ready line; it is then ended.

    The child runs in ``folder``, an empty one: a ``python -c`` program has its working
    folder first on its path, which from a checkout's root would shadow ``--compare``'s
    checkout (and this one's, from the other's root).
    """
    start = time.perf_counter()
    child = subprocess.Popen(
        case.argv, env=case.env, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
        stderr=subprocess.PIPE, text=True, cwd=folder,
    )
    assert child.stdout is not None
    try:
        for line in child.stdout:
            if line.startswith(MARKER):
                elapsed = time.perf_counter() - start
                break
        else:
            raise RuntimeError(f"{case.name}: no ready line:\n{child.communicate()[1][-2000:]}")
        child.stdout.close()  # the rest of its output is not wanted
        child.wait(timeout=60)
    finally:
        if child.poll() is None:
            child.kill()
            child.wait()
    return elapsed


def _other_checkout(env: dict[str, str], checkout: str) -> dict[str, str]:
    """``env`` with another checkout of j5aio first on the path (``--compare``)."""
    return {**env, "PYTHONPATH": os.pathsep.join([checkout, env["PYTHONPATH"]])}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=15, help="runs of each case (default 15)")
    parser.add_argument("--kit", default="", help="the simulated kit (J5AIO_KIT; default kit)")
    parser.add_argument(
        "--compare", metavar="CHECKOUT", default="",
        help="another checkout of j5aio (before a change, say): its async and sync cases "
        "run in the same interleaved rounds",
    )
    parser.add_argument(
        "--imports", action="store_true",
        help="also count the modules and dataclasses each j5aio case has imported when ready",
    )
    options = parser.parse_args()

    sim = {"J5AIO_ENV": "sim", **({"J5AIO_KIT": options.kit} if options.kit else {})}
    cases = [
        Case("j5aio async, simulated kit", [sys.executable, "-c", ASYNC_PROGRAM], j5aio_env(**sim)),
        Case("j5aio sync, simulated kit", [sys.executable, "-c", SYNC_PROGRAM], j5aio_env(**sim)),
    ]
    if options.compare:
        cases += [
            Case(f"{case.name} ({options.compare})", case.argv,
                 _other_checkout(case.env, options.compare))
            for case in list(cases)
        ]
    floor = Case("floor: anyio.run, no j5aio", [sys.executable, "-c", FLOOR_PROGRAM], j5aio_env())
    cases.append(floor)
    peer = j5_python()
    j5 = None
    if peer is not None:
        j5 = Case("j5 console robot", [str(peer), "-c", J5_PROGRAM], j5aio_env())
        cases.append(j5)
    with tempfile.TemporaryDirectory(prefix="j5aio-bench-startup-") as folder:
        run_interleaved(cases, options.rounds, functools.partial(time_to_ready, folder=folder))
        counted = [
            case
            for case in cases
            if (case.name.startswith("j5aio") or case is floor) and options.imports
        ]
        imported = {case.name: imports_at_ready(case, folder) for case in counted}
    print(f"process start -> robot ready, {options.rounds} interleaved rounds")
    print_table("time to a ready robot", cases, "ms", reference=j5, scale=1000)
    limit = floor.median * 1000 + GOAL_ABOVE_FLOOR_MS
    print(
        f"\ngoal (<= the floor + {GOAL_ABOVE_FLOOR_MS:.0f} ms = {limit:.1f} ms on the "
        "simulated kit):"
    )
    for case in cases[:2]:
        ms = case.median * 1000
        above = (case.median - floor.median) * 1000
        print(
            f"  {case.name:<27} {ms:7.1f} ms  floor + {above:5.1f} ms  "
            f"{'met' if ms <= limit else 'NOT met'}"
        )
    sync_share = (cases[1].median - cases[0].median) * 1000
    print(f"  the sync runtime's share (sync - async): {sync_share:.1f} ms")
    print(
        "\npaired within each round (the case minus the floor of the same round: the "
        "machine's drift between rounds falls out), median and quartiles:"
    )
    for case in cases:
        if case.name.startswith("j5aio"):
            low, middle, high = paired_above(case, floor)
            print(
                f"  {case.name:<40} floor + {middle * 1000:5.1f} ms  "
                f"({low * 1000:5.1f} to {high * 1000:5.1f})"
            )
    if imported:
        print(
            "\nimported when ready (modules: all, j5aio's; j5aio's dataclasses; "
            "garbage collections so far, and their time):"
        )
        for name, (modules, ours, dataclasses, collections, seconds) in imported.items():
            print(
                f"  {name:<40} {modules:5d} {ours:5d} {dataclasses:5d} "
                f"{collections:5d} {seconds * 1000:6.2f} ms"
            )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

"""How long importing j5aio takes, against importing j5 0.12, each in a fresh interpreter.

Every case is timed inside a new child interpreter (``time.perf_counter`` around the
import statements alone, so the interpreter's own start-up is left out), with the number
of modules loaded after it. Cases:

* ``import j5`` (j5 0.12, in its own venv made by ``_peers.py``), ``import j5aio`` and
  ``import j5aio.sync``: the packages themselves;
* what a first program imports: j5's quick start (``BaseRobot``, ``BoardGroup``, a power
  board and its console backend); the same names from j5aio's sync facade; the README's
  first sync program (``from j5aio.sync import KitRobot``) and first async program
  (``anyio`` and ``j5aio.kit.KitRobot``);
* the hardware stack of the simulated kit: the hardware backends a simulated start
  makes (power, motor and servo boards, the Arduinos), imported after ``j5aio.kit``, so
  the figure is what the backends, their codecs and transports add (with the boards
  and components they drive).

Beside each figure: the modules loaded, and how many of them are j5aio's, and the
dataclasses j5aio's modules define (each one costs a start the generation of its
methods, about 0.3 ms for a frozen one on Python 3.11).

Rounds are interleaved and shuffled; the table shows medians and the ratio to j5. Run::

    python bench/bench_import.py [--rounds 15]

Goals: ``import j5aio`` and ``import j5aio.sync`` take at most 1.0x
``import j5`` in the same run.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _children import (  # type: ignore[import-not-found]
    Case,
    j5_python,
    j5aio_env,
    print_table,
    run_interleaved,
    run_reporting,
)

GOAL_RATIO = 1.0

CHILD = """\
import sys, time
{setup}
start = time.perf_counter()
{statements}
elapsed = time.perf_counter() - start
ours = [m for name, m in list(sys.modules.items()) if name.split(".")[0] == "j5aio"]
made = sum(
    1 for m in ours for v in list(vars(m).values())
    if isinstance(v, type) and v.__module__ == m.__name__ and "__dataclass_fields__" in vars(v)
)
print("BENCH", elapsed, len(sys.modules), len(ours), made)
"""

# What a simulated start of the default kit imports from the hardware backends.
HARDWARE_STACK = (
    "import j5aio.backends.hardware.sb.arduino\n"
    "import j5aio.backends.hardware.sr.v4.motor_board\n"
    "import j5aio.backends.hardware.sr.v4.power_board\n"
    "import j5aio.backends.hardware.sr.v4.ruggeduino\n"
    "import j5aio.backends.hardware.sr.v4.servo_board"
)

J5_FIRST = (
    "from j5 import BaseRobot, BoardGroup\n"
    "from j5.backends.console.sr.v4 import SRV4PowerBoardConsoleBackend\n"
    "from j5.boards.sr.v4 import PowerBoard"
)
J5AIO_J5_FIRST = (
    "from j5aio.sync import BaseRobot, BoardGroup\n"
    "from j5aio.backends.console.sr.v4 import SRV4PowerBoardConsoleBackend\n"
    "from j5aio.boards.sr.v4 import PowerBoard"
)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=15, help="runs of each case (default 15)")
    options = parser.parse_args()

    modules: dict[str, list[tuple[int, ...]]] = {}

    def case(name: str, python: str, statements: str, setup: str = "") -> Case:
        env = j5aio_env()
        child = CHILD.format(setup=setup, statements=statements)
        return Case(name, [python, "-c", child], env)

    peer = j5_python()
    mine = sys.executable
    cases: list[Case] = []
    j5 = j5_first = None
    if peer is not None:
        j5 = case("import j5", str(peer), "import j5")
        j5_first = case("j5 quick start imports", str(peer), J5_FIRST)
        cases += [j5, j5_first]
    core = case("import j5aio", mine, "import j5aio")
    sync = case("import j5aio.sync", mine, "import j5aio.sync")
    cases += [
        core,
        sync,
        case("j5aio.sync, j5 quick start imports", mine, J5AIO_J5_FIRST),
        case("first sync program (README)", mine, "from j5aio.sync import KitRobot"),
        case("first async program (README)", mine, "import anyio\nfrom j5aio.kit import KitRobot"),
    ]
    hardware = case(
        "hardware stack, simulated kit", mine, HARDWARE_STACK,
        setup="import anyio\nfrom j5aio.kit import KitRobot",
    )
    cases.append(hardware)

    def measure(c: Case) -> float:
        elapsed, *counts = run_reporting(c, "BENCH").split()
        modules.setdefault(c.name, []).append(tuple(int(n) for n in counts))
        return float(elapsed)

    def loaded(c: Case) -> str:
        everything, ours, dataclasses = max(modules[c.name])
        if c.argv[0] != mine:
            return f"{everything} modules"
        return f"{everything} modules ({ours} j5aio), {dataclasses} j5aio dataclasses"

    run_interleaved(cases, options.rounds, measure)
    print(f"import time, fresh interpreter each run, {options.rounds} interleaved rounds")
    print_table("the packages", [c for c in (j5, core, sync) if c is not None], "ms",
                reference=j5, scale=1000, extra=loaded)
    print_table("what a first program imports",
                [c for c in cases if c not in (j5, core, sync, hardware)],
                "ms", reference=j5_first, scale=1000, extra=loaded)
    print_table("added by the hardware backends (after j5aio.kit)", [hardware], "ms",
                reference=None, scale=1000, extra=loaded)
    if j5 is None:
        print("\nno j5 to compare with: goals not checked")
        return 0
    print(f"\ngoals (<= {GOAL_RATIO:.1f}x import j5):")
    for c in (core, sync):
        ratio = c.median / j5.median
        print(f"  {c.name:<18} {ratio:5.2f}x  {'met' if ratio <= GOAL_RATIO else 'NOT met'}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

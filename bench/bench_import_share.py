"""How much of a start's module loading is CPython's import machinery, and how much the code.

A start on the simulated kit loads some 120 j5aio modules. This bench asks how much of
that time merging modules could ever save: it times, in fresh interpreters, interleaved
round by round,

* importing the modules a sim-kit start loads (listed by a first child that makes the
  robot), one after another, after ``anyio.run`` has loaded asyncio and anyio;
* importing as many *empty* modules of a temporary package, the same way: what the
  import machinery alone costs (finding, reading and unmarshalling a file, making the
  module), which is all that merging modules could take away.

The rest is the code itself: unmarshalling the byte code and running the module bodies
(classes, functions, tables), which merged modules would still have to do. Run::

    python bench/bench_import_share.py [--rounds 11] [--kit NAME]
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _children import j5aio_env  # type: ignore[import-not-found]

# Lists the modules a start loads beyond what anyio.run loads (j5aio's and its plugins').
LIST_PROGRAM = """
import sys
import anyio

async def nothing() -> None:
    pass

anyio.run(nothing)
before = set(sys.modules)
from j5aio.kit import KitRobot

async def main() -> None:
    async with KitRobot():
        pass

anyio.run(main)
print(*sorted(set(sys.modules) - before))
"""

# Imports the modules named on the command line, timed, after anyio.run.
IMPORT_PROGRAM = """
import importlib
import sys
import time
import anyio

async def nothing() -> None:
    pass

anyio.run(nothing)
names = sys.argv[1:]
start = time.perf_counter()
for name in names:
    importlib.import_module(name)
print(time.perf_counter() - start)
"""


def _run(argv: list[str], env: dict[str, str], cwd: str) -> str:
    done = subprocess.run(
        argv, env=env, cwd=cwd, capture_output=True, text=True, timeout=120, check=False
    )
    if done.returncode != 0:
        raise RuntimeError(f"{argv[:3]} failed:\n{done.stderr[-2000:]}")
    return done.stdout


def empty_package(folder: Path, count: int) -> list[str]:
    """Write a package of ``count`` empty modules in ``folder``; return their names."""
    package = folder / "j5aio_bench_empty"
    package.mkdir()
    (package / "__init__.py").write_text("")
    for number in range(count):
        (package / f"module_{number}.py").write_text(f"NUMBER = {number}\n")
    return [f"j5aio_bench_empty.module_{number}" for number in range(count)]


def main() -> int:
    """Print the two medians and the share of the machinery."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=11, help="interleaved rounds")
    parser.add_argument("--kit", default="", help="a named simulated kit (default: the default)")
    options = parser.parse_args()
    env = j5aio_env(J5AIO_ENV="sim", **({"J5AIO_KIT": options.kit} if options.kit else {}))
    env.pop("PYTHONDONTWRITEBYTECODE", None)  # (time reading byte code, not compiling it)
    with tempfile.TemporaryDirectory(prefix="j5aio-bench-imports-") as folder:
        start_modules = _run([sys.executable, "-c", LIST_PROGRAM], env, folder).split()
        empty = empty_package(Path(folder), len(start_modules))
        env["PYTHONPATH"] = os.pathsep.join([folder, env.get("PYTHONPATH", "")])
        cases = {"the start's modules": start_modules, "as many empty modules": empty}
        times: dict[str, list[float]] = {name: [] for name in cases}
        for round_number in range(options.rounds + 1):  # (the first round writes byte code)
            for name, modules in cases.items():
                seconds = float(_run([sys.executable, "-c", IMPORT_PROGRAM, *modules], env, folder))
                if round_number:
                    times[name].append(seconds)
    print(f"importing {len(start_modules)} modules after anyio.run, {options.rounds} rounds:")
    for name, values in times.items():
        print(f"  {name:<22} median {statistics.median(values) * 1000:6.1f} ms")
    machinery = statistics.median(times["as many empty modules"])
    whole = statistics.median(times["the start's modules"])
    print(
        f"the import machinery: {machinery / whole:.0%} of it, "
        f"{machinery / len(start_modules) * 1e6:.0f} us a module (the most merging could save)"
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

"""attach on a named port: how long identifying the board takes, quick round against the old way.

Each board is served by its simulator on a pseudo-terminal (which, like a port with no
USB identity, tells nothing of its kind), and ``attach(path)`` identifies it: first every
kind asked over one opening of the port per baud rate, with short waits. Beside it, the
old way, every candidate kind in turn with its full identification waits
(``identify._identify``, the round ``attach`` still falls back on). The Bee Board of the
example kit (``tests/example_kit``) is identified after every one of j5aio's own kinds.

Goal: ``attach`` on a named port <= 1 s (it took 15.7 s for the Bee Board).

Run: ``PYTHONPATH=$PWD python bench/bench_attach.py [--rounds 5] [--no-old]``
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from collections.abc import Callable
from pathlib import Path

os.environ.setdefault("J5AIO_LOCK_PORT", "0")
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "example_kit"))

import anyio
from beekit.simulator import BeeSimulator

from j5aio.backends.hardware import identify, port_search
from j5aio.simulator.serve import serve_on_pty
from j5aio.simulator.sr_motor_fw4 import SRMotorBoardFw4Simulator
from j5aio.simulator.sr_ruggeduino_fw1 import SRRuggeduinoSimulator

BOARDS: dict[str, Callable[[], object]] = {
    "bee (a plugin's, tried last)": lambda: BeeSimulator("BEE1"),
    "sr-ruggeduino-fw1": lambda: SRRuggeduinoSimulator("RD1"),
    "sr-motor-fw4": lambda: SRMotorBoardFw4Simulator("MB1"),
}


async def time_attach(make: Callable[[], object]) -> float:
    with serve_on_pty(make()) as server:  # type: ignore[arg-type]
        start = time.perf_counter()
        board = await identify.attach(server.path)
        elapsed = time.perf_counter() - start
        await board.close()
    return elapsed


async def time_old(make: Callable[[], object]) -> float:
    with serve_on_pty(make()) as server:  # type: ignore[arg-type]
        backends = identify.serial_backends()
        start = time.perf_counter()
        board = await port_search.identify_on_port(server.path, server.path, backends, None, 1.0)
        elapsed = time.perf_counter() - start
        await board.close()
    return elapsed


async def main(rounds: int, old: bool) -> None:
    print(f"attach on a pty, median of {rounds} (seconds)")
    print(f"{'board':32} {'attach':>8} {'old way':>8}")
    for name, make in BOARDS.items():
        new_times = [await time_attach(make) for _ in range(rounds)]
        old_text = "-"
        if old:
            old_times = [await time_old(make) for _ in range(max(1, rounds // 2))]
            old_text = f"{statistics.median(old_times):8.2f}"
        print(f"{name:32} {statistics.median(new_times):8.2f} {old_text:>8}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--no-old", action="store_true", help="skip the old way (slow)")
    arguments = parser.parse_args()
    anyio.run(main, arguments.rounds, not arguments.no_old)

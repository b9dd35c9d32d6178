"""What reaching a wrapped container's item costs through the sync facade, beside the core.

Measures, on the simulated sr2023 kit (``J5AIO_ENV=sim``), the median time of
``arduino.pins[3]``, ``servo_board.servos[0]`` and ``motor_board.motors[0]``: through the
sync wrappers (``j5aio.sync.KitRobot``) and on the core objects behind them. No board is
spoken to: this is the cost of the wrappers alone. Run::

    python bench/bench_sync_wrappers.py [--accesses 20000] [--rounds 7]

Goal: a wrapped container access through the facade <= 2 µs.
"""

from __future__ import annotations

import argparse
import os
import statistics
import time
from collections.abc import Callable
from typing import Any


def per_access(access: Callable[[], Any], accesses: int) -> float:
    """The time of one ``access()``, in µs, over ``accesses`` calls."""
    start = time.perf_counter()
    for _ in range(accesses):
        access()
    return (time.perf_counter() - start) / accesses * 1e6


def main() -> None:
    """Measure and print the medians of each access, facade and core."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--accesses", type=int, default=20000)
    parser.add_argument("--rounds", type=int, default=7)
    args = parser.parse_args()
    os.environ["J5AIO_ENV"] = "sim"
    os.environ.setdefault("J5AIO_KIT", "sr2023")

    from j5aio.sync import KitRobot, shutdown

    robot = KitRobot()
    ard, servo_board, motor_board = robot.arduinos[0], robot.servo_boards[0], robot.motor_boards[0]
    cases: dict[str, tuple[Callable[[], Any], Callable[[], Any]]] = {
        "arduino.pins[3]": (lambda: ard.pins[3], lambda: ard._core.pins[3]),
        "servo_board.servos[0]": (
            lambda: servo_board.servos[0], lambda: servo_board._core.servos[0],
        ),
        "motor_board.motors[0]": (
            lambda: motor_board.motors[0], lambda: motor_board._core.motors[0],
        ),
        "robot.motor_boards[0].motors[0]": (
            lambda: robot.motor_boards[0].motors[0],
            lambda: robot._core.motor_boards[0].motors[0],
        ),
    }
    figures: dict[str, tuple[list[float], list[float]]] = {name: ([], []) for name in cases}
    for _ in range(args.rounds):
        for name, (facade, core) in cases.items():
            figures[name][0].append(per_access(facade, args.accesses))
            figures[name][1].append(per_access(core, args.accesses))
    print(f"{'access':<34}{'facade µs':>11}{'core µs':>10}{'overhead µs':>13}")
    for name, (facade_times, core_times) in figures.items():
        facade_median = statistics.median(facade_times)
        core_median = statistics.median(core_times)
        print(
            f"{name:<34}{facade_median:>11.2f}{core_median:>10.2f}"
            f"{facade_median - core_median:>13.2f}"
        )
    shutdown()


if __name__ == "__main__":
    main()

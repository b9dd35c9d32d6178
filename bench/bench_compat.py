"""A call through a competition's API on j5aio beside the same call through ``j5aio.sync``.

The competition APIs (:mod:`j5aio.compat`) are thin layers on the sync facade: a call
through one should cost no more than the same call made with ``j5aio.sync`` itself. This
bench makes one robot on the simulated kit (``sr2023``, in this process) and times each
call both ways, on the same board objects, in interleaved rounds:

* ``motor power =``: ``robot.motor_board.motors[0].power = 0.5`` (sr-robot3) beside
  ``kit.motor_boards[0].motors[0].power = 0.5`` (``j5aio.sync``);
* ``motor power``: reading it back;
* ``battery voltage``: ``robot.power_board.battery_sensor.voltage``;
* ``servo position =``: ``servos[0].position = 0.25``;
* ``digital_read``: an input pin of the Arduino;
* ``analog_read``: A0 (sr-robot3 also rescales to its volts).

Each round times ``--calls`` calls of each case on each side, in batches of ``--batch``
calls, the two sides taking turns batch by batch (so that the load of a shared machine
falls on both alike); the figure is the median of the batches' mean time per call, in
µs, with the ratio compat / sync.

sbot (``j5aio.compat.sbot``) is measured the same way once its module exists: its cases
go in :data:`SBOT_CASES` (``motors.set_power(0, 0.5)`` beside the sync call on the same
motor, ...), run on the ``sb2024`` kit in a child process (one robot per process).

Run::

    PYTHONPATH=$PWD python bench/bench_compat.py [--calls 2000] [--rounds 7] [--batch 50]

Goal (issue 20): compat / sync <= 1.0 (within the noise of a shared machine: a few %).
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from collections.abc import Callable
from typing import Any

Case = tuple[str, Callable[[], Any], Callable[[], Any]]


def sr_robot3_cases() -> list[Case]:
    """The sr-robot3 cases: (name, the compat call, the same call through j5aio.sync)."""
    os.environ["J5AIO_ENV"] = "sim"
    os.environ["J5AIO_KIT"] = "sr2023"
    import logging

    from j5aio.compat.sr_robot3 import A0, INPUT, Robot

    robot = Robot(wait_for_start=False)
    logging.getLogger().setLevel(logging.WARNING)  # (Robot logs at INFO, as sr-robot3)
    kit = robot._kit
    motor, core_motor = robot.motor_board.motors[0], kit.motor_boards[0].motors[0]
    servo, core_servo = robot.servo_board.servos[0], kit.servo_boards[0].servos[0]
    battery, core_battery = (
        robot.power_board.battery_sensor, kit.power_board.battery_sensor)
    arduino, core_arduino = robot.arduino, kit.ruggeduinos[0]
    arduino.pins[3].mode = INPUT
    pin, core_pin = arduino.pins[3], core_arduino.pins[3]
    analogue, core_analogue = arduino.pins[A0], core_arduino.pins[14]

    def set_power() -> None:
        motor.power = 0.5

    def set_core_power() -> None:
        core_motor.power = 0.5

    def set_position() -> None:
        servo.position = 0.25

    def set_core_position() -> None:
        core_servo.position = 0.25

    return [
        ("motor power =", set_power, set_core_power),
        ("motor power", lambda: motor.power, lambda: core_motor.power),
        ("battery voltage", lambda: battery.voltage, lambda: core_battery.voltage),
        ("servo position =", set_position, set_core_position),
        ("digital_read", pin.digital_read, core_pin.digital_read),
        ("analog_read", analogue.analog_read, core_analogue.analogue_read),
    ]


#: sbot's cases, once ``j5aio.compat.sbot`` exists: a function giving
#: ``(name, compat call, sync call)`` triples on the sb2024 kit, as :func:`sr_robot3_cases`.
SBOT_CASES: Callable[[], list[Case]] | None = None


def per_call(call: Callable[[], Any], calls: int) -> float:
    """The mean time of one call, in µs."""
    start = time.perf_counter()
    for _ in range(calls):
        call()
    return (time.perf_counter() - start) / calls * 1e6


def measure(cases: list[Case], calls: int, rounds: int, batch: int) -> None:
    for _, compat, sync in cases:  # (once each first: nothing is measured cold)
        compat()
        sync()
    figures: dict[str, tuple[list[float], list[float]]] = {
        name: ([], []) for name, _, _ in cases}
    batches = max(1, calls // batch)
    for _ in range(rounds):
        for name, compat, sync in cases:
            mine, theirs = figures[name]
            for number in range(batches):  # (small batches, in turn: drift hits both)
                if number % 2:
                    theirs.append(per_call(sync, batch))
                    mine.append(per_call(compat, batch))
                else:
                    mine.append(per_call(compat, batch))
                    theirs.append(per_call(sync, batch))
    print(f"{'call':<20}{'compat µs':>11}{'sync µs':>10}{'ratio':>8}")
    for name, (mine, theirs) in figures.items():
        compat_us, sync_us = statistics.median(mine), statistics.median(theirs)
        print(f"{name:<20}{compat_us:>11.1f}{sync_us:>10.1f}{compat_us / sync_us:>8.2f}")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--calls", type=int, default=2000, help="calls per case per round")
    parser.add_argument("--rounds", type=int, default=7, help="rounds over the cases")
    parser.add_argument(
        "--batch", type=int, default=50, help="calls per timed batch (sides alternate)")
    args = parser.parse_args()
    print(f"sr-robot3 on the simulated sr2023 kit: {args.calls} calls x {args.rounds} rounds")
    measure(sr_robot3_cases(), args.calls, args.rounds, args.batch)
    if SBOT_CASES is None:
        print("sbot: j5aio.compat.sbot's cases are not written yet (see SBOT_CASES)")
    return 0


if __name__ == "__main__":
    sys.exit(main())

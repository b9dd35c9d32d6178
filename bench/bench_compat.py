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

sbot (``j5aio.compat.sbot``) is measured the same way on the ``sb2024`` kit, in a child
process (one robot per process; ``--api sbot`` runs only that part), with the same
j5aio objects as the sync side:

* ``motors.set_power``: ``motors.set_power(0, 0.5)`` beside ``motor.power = 0.5``;
* ``motors.get_power``: reading it back;
* ``battery data``: ``power.get_battery_data()`` beside the battery sensor's voltage and
  current;
* ``is_output_on``: ``power.is_output_on(0)`` beside ``output.is_enabled``;
* ``set_position``: ``servos.set_position(0, 0.25)`` beside ``servo.position = 0.25``;
* ``digital_read``, ``analog_read``: pin 3 and A0 of the Arduino.

Run::

    PYTHONPATH=$PWD python bench/bench_compat.py [--calls 2000] [--rounds 7] [--batch 50]
        [--api sr-robot3|sbot]

Goal: compat / sync <= 1.0 (within the noise of a shared machine: a few %).
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
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


def sbot_cases() -> list[Case]:
    """The sbot cases, on the sb2024 kit: (name, the compat call, the call through j5aio.sync)."""
    os.environ.update({"J5AIO_ENV": "sim", "J5AIO_KIT": "sb2024", "SBOT_SKIP_WAIT_START": "1"})
    import logging

    from j5aio.compat.sbot import AnalogPin, GPIOPinMode, arduino, motors, power, servos, utils
    from j5aio.compat.sbot._robot import boards

    utils.load_boards()
    logging.getLogger().setLevel(logging.WARNING)  # (sbot logs at INFO)
    motor = boards.motor(0).component
    servo = boards.servo(0).component
    servos.set_position(0, 0.25)  # (gives the servo sbot's pulse limits first)
    board = boards.power_board()
    output, battery = board.outputs[0], board.battery_sensor
    arduino.set_pin_mode(3, GPIOPinMode.INPUT)
    pin, analogue = boards.arduino().pins[3], boards.arduino().pins[AnalogPin.A0]

    def set_power() -> None:
        motors.set_power(0, 0.5)

    def set_core_power() -> None:
        motor.power = 0.5

    def set_position() -> None:
        servos.set_position(0, 0.25)

    def set_core_position() -> None:
        servo.position = 0.25

    return [
        ("motors.set_power", set_power, set_core_power),
        ("motors.get_power", lambda: motors.get_power(0), lambda: motor.power),
        ("battery data", power.get_battery_data, lambda: (battery.voltage, battery.current)),
        ("is_output_on", lambda: power.is_output_on(0), lambda: output.is_enabled),
        ("set_position", set_position, set_core_position),
        ("digital_read", lambda: arduino.digital_read(3), pin.digital_read),
        ("analog_read", lambda: arduino.analog_read(AnalogPin.A0), analogue.analogue_read),
    ]


#: The cases of each API, by the name ``--api`` gives it.
CASES: dict[str, tuple[str, Callable[[], list[Case]]]] = {
    "sr-robot3": ("sr-robot3 on the simulated sr2023 kit", sr_robot3_cases),
    "sbot": ("sbot on the simulated sb2024 kit", sbot_cases),
}


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
    parser.add_argument(
        "--api", choices=tuple(CASES), help="measure only this API (default: each, in turn)")
    args = parser.parse_args()
    if args.api is None:  # one robot per process: each API in a child of its own
        options = ["--calls", str(args.calls), "--rounds", str(args.rounds),
                   "--batch", str(args.batch)]
        for api in CASES:
            done = subprocess.run([sys.executable, __file__, *options, "--api", api], check=False)
            if done.returncode:
                return done.returncode
        return 0
    title, cases = CASES[args.api]
    print(f"{title}: {args.calls} calls x {args.rounds} rounds", flush=True)
    measure(cases(), args.calls, args.rounds, args.batch)
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""What a call through ``j5aio.compat.sbot`` costs beside the same call through ``j5aio.sync``.

On the simulated sb2024 kit, in one run, with the rounds interleaved so that machine
noise hits both alike, the median time of:

* ``motors.set_power(0, 0.5)`` against ``motor.power = 0.5`` on the same j5aio motor;
* ``motors.get_power(0)`` against ``motor.power``;
* ``servos.set_position(0, 0.5)`` against ``servo.position = 0.5``;
* ``arduino.digital_read(3)`` against ``pin.digital_read()``;
* ``power.is_output_on(0)`` against ``output.is_enabled``.

Goal (the compatibility issue): a call through the compat API costs no more than one
through ``j5aio.sync``, that is the difference is the compat layer's own Python (checks
and sbot's arithmetic), small beside the facade call both make. Run::

    python bench/bench_compat_sbot.py [--calls 2000] [--rounds 5]
"""

from __future__ import annotations

import argparse
import os
import socket
import statistics
import time
from collections.abc import Callable


def _free_port() -> str:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return str(probe.getsockname()[1])


def _median_us(call: Callable[[], object], calls: int) -> float:
    times = []
    for _ in range(calls):
        start = time.perf_counter()
        call()
        times.append(time.perf_counter() - start)
    return statistics.median(times) * 1e6


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--calls", type=int, default=2000)
    parser.add_argument("--rounds", type=int, default=5)
    args = parser.parse_args()

    os.environ.update({
        "J5AIO_ENV": "sim",
        "J5AIO_KIT": "sb2024",
        "J5AIO_LOCK_PORT": _free_port(),
        "SBOT_SKIP_WAIT_START": "1",
    })
    from j5aio.compat.sbot import arduino, motors, power, servos, utils
    from j5aio.compat.sbot._robot import boards
    from j5aio.sync import shutdown

    utils.load_boards()
    motor = boards.motor(0).component
    servo = boards.servo(0).component
    servos.set_position(0, 0.5)  # (the compat layer gives the servo sbot's limits first)
    pin = boards.arduino().pins[3]
    output = boards.power_board().outputs[0]

    def sync_set_power() -> None:
        motor.power = 0.5

    def sync_set_position() -> None:
        servo.position = 0.5

    pairs: dict[str, tuple[Callable[[], object], Callable[[], object]]] = {
        "set motor power": (lambda: motors.set_power(0, 0.5), sync_set_power),
        "get motor power": (lambda: motors.get_power(0), lambda: motor.power),
        "set servo position": (lambda: servos.set_position(0, 0.5), sync_set_position),
        "digital read": (lambda: arduino.digital_read(3), pin.digital_read),
        "is output on": (lambda: power.is_output_on(0), lambda: output.is_enabled),
    }
    results: dict[str, tuple[list[float], list[float]]] = {
        name: ([], []) for name in pairs
    }
    for _ in range(args.rounds):
        for name, (compat, sync) in pairs.items():
            results[name][0].append(_median_us(compat, args.calls))
            results[name][1].append(_median_us(sync, args.calls))
    print(f"{'call':<20} {'compat µs':>10} {'sync µs':>10} {'extra µs':>10}")
    for name, (compat_times, sync_times) in results.items():
        ours, theirs = statistics.median(compat_times), statistics.median(sync_times)
        print(f"{name:<20} {ours:>10.1f} {theirs:>10.1f} {ours - theirs:>10.1f}")
    shutdown()


if __name__ == "__main__":
    main()

"""A robot's control loop on today's SR kit (sr2023): j5aio vs sr-robot3, wire-timed.

Each iteration of the loop touches all four serial boards of the kit, as a robot's loop
does: it reads the battery voltage (power board, fw 4.4), sets a motor's power (motor
board, fw 4.4), sets a servo's position (servo board, fw 4.3) and reads a digital pin
(SR Arduino, fw 2). Every board is a j5aio simulator served on a pseudo-terminal by a
process of its own, with ``--uart-timing``: each reply comes only after the time the
board's serial line takes to carry the request and the reply, as on the real wire.

* j5aio touches the four boards at once (one task each, in a task group): the loop
  takes as long as the slowest board.
* sr-robot3 (Student Robotics' own library, from PyPI: ``pip install sr-robot3``, and
  ``opencv-python-headless`` for its vision import) does what its programs do, one
  board after another.

Each library has its own four simulators (a port is opened by one program at a time).
On the wire alone, one iteration is about 1.2 (power), 1.6 (motor), 1.8 (servo) and
0.35 ms (Arduino) at 115 200 baud: 4.95 ms one after another, 1.8 ms at once (0.37x);
what each library adds per request decides how far below or above that the ratio lands.
Batches of iterations alternate between the two, so that drift affects both alike;
every figure is a median. Goal: j5aio's loop <= 0.35x sr-robot3's.

Run: ``python bench/bench_kits.py [--iterations N] [--repeats R]`` (where sr-robot3 is
installed, e.g. the ``peers`` tox environment; without it only j5aio is measured).
"""

from __future__ import annotations

import argparse
import contextlib
import importlib
import importlib.util
import logging
import statistics
import subprocess
import sys
import time
from collections.abc import Iterator
from typing import Any

import anyio

from j5aio.backends.hardware.sr.v4 import (
    SRArduinoHardwareBackend,
    SRV4MotorBoardFw4HardwareBackend,
    SRV4PowerBoardFw4HardwareBackend,
    SRV4ServoBoardFw4HardwareBackend,
)
from j5aio.boards.sr.v4 import MotorBoardFw4, PowerBoardFw4, ServoBoardFw4, SRArduinoBoard
from j5aio.components.gpio_pin import GPIOPinMode

#: The simulators of the sr2023 kit's serial boards, by the role they play in the loop.
BOARDS = {
    "power": "sr-power-fw4",
    "motor": "sr-motor-fw4",
    "servo": "sr-servo-fw4",
    "arduino": "sr-arduino-fw2",
}
GOAL = 0.35


@contextlib.contextmanager
def served_kit(prefix: str) -> Iterator[dict[str, str]]:
    """Serve the kit's four boards, wire-timed, each from its own process; yield their ptys."""
    processes: list[subprocess.Popen[str]] = []
    try:
        paths = {}
        for role, name in BOARDS.items():
            process = subprocess.Popen(
                [
                    sys.executable, "-m", "j5aio", "simulate", name, "--pty", "--uart-timing",
                    "--time-scale", "0.05", "--serial", f"{prefix}{role.upper()}",
                ],
                stdout=subprocess.PIPE,
                stderr=subprocess.DEVNULL,
                text=True,
            )
            processes.append(process)
            assert process.stdout is not None
            paths[role] = process.stdout.readline().strip()
        yield paths
    finally:
        for process in processes:
            process.terminate()
        for process in processes:
            process.wait(5)


class J5aioLoop:
    """The loop through j5aio: the four boards at once."""

    def __init__(self, boards: dict[str, Any]) -> None:
        self.power: PowerBoardFw4 = boards["power"]
        self.motor: MotorBoardFw4 = boards["motor"]
        self.servo: ServoBoardFw4 = boards["servo"]
        self.arduino: SRArduinoBoard = boards["arduino"]

    @classmethod
    async def attach(cls, paths: dict[str, str]) -> J5aioLoop:
        backends: dict[str, Any] = {
            "power": SRV4PowerBoardFw4HardwareBackend,
            "motor": SRV4MotorBoardFw4HardwareBackend,
            "servo": SRV4ServoBoardFw4HardwareBackend,
            "arduino": SRArduinoHardwareBackend,
        }
        boards = {}
        for role, backend in backends.items():
            board = await backend.attach(paths[role])
            await board.setup()
            boards[role] = board
        loop = cls(boards)
        await loop.arduino.pins[3].set_mode(GPIOPinMode.DIGITAL_INPUT)
        return loop

    async def iteration(self, index: int) -> None:
        power = 0.5 if index % 2 else -0.5

        async with anyio.create_task_group() as group:
            group.start_soon(self.power.battery_sensor.get_voltage)
            group.start_soon(self.motor.motors[0].set_power, power)
            group.start_soon(self.servo.servos[0].set_position, power)
            group.start_soon(self.arduino.pins[3].digital_read)

    async def batch(self, iterations: int) -> list[float]:
        times = []
        for index in range(iterations):
            start = time.perf_counter()
            await self.iteration(index)
            times.append(time.perf_counter() - start)
        return times

    async def close(self) -> None:
        for board in (self.power, self.motor, self.servo, self.arduino):
            await board.close()


class SRRobot3Loop:
    """The same loop through sr-robot3: one board after another."""

    def __init__(self, paths: dict[str, str]) -> None:
        robot3: Any = importlib.import_module("sr.robot3")  # untyped here: not j5aio's dep
        logging.getLogger("sr.robot3").setLevel(logging.ERROR)
        self.robot = robot3.Robot(
            manual_boards={
                "PBv4B": [paths["power"]], "MCv4B": [paths["motor"]],
                "SBv4B": [paths["servo"]], "Arduino": [paths["arduino"]],
            },
            wait_for_start=False,
        )
        self.robot.arduino.pins[3].mode = robot3.INPUT

    def iteration(self, index: int) -> None:
        robot = self.robot
        power = 0.5 if index % 2 else -0.5
        robot.power_board.battery_sensor.voltage  # noqa: B018 - a read over the wire
        robot.motor_board.motors[0].power = power
        robot.servo_board.servos[0].position = power
        robot.arduino.pins[3].digital_read()

    def batch(self, iterations: int) -> list[float]:
        times = []
        for index in range(iterations):
            start = time.perf_counter()
            self.iteration(index)
            times.append(time.perf_counter() - start)
        return times


async def run(iterations: int, repeats: int) -> tuple[float, float | None]:
    """Return the median loop time of j5aio and of sr-robot3 (None if not installed), in ms."""
    have_peer = importlib.util.find_spec("sr") is not None and (
        importlib.util.find_spec("sr.robot3") is not None
    )
    with contextlib.ExitStack() as stack:
        ours_paths = stack.enter_context(served_kit("J5AIO"))
        theirs_paths = stack.enter_context(served_kit("SRR3")) if have_peer else None
        ours = await J5aioLoop.attach(ours_paths)
        theirs = SRRobot3Loop(theirs_paths) if theirs_paths is not None else None
        ours_times: list[float] = []
        theirs_times: list[float] = []
        await ours.batch(5)  # warm up
        if theirs is not None:
            theirs.batch(5)
        for _ in range(repeats):  # interleaved batches
            ours_times += await ours.batch(iterations)
            if theirs is not None:
                theirs_times += theirs.batch(iterations)
        await ours.close()
    # sr-robot3 resets its boards at exit, after their simulators have gone: quiet.
    logging.getLogger("sr.robot3").setLevel(logging.CRITICAL)
    ours_ms = statistics.median(ours_times) * 1e3
    theirs_ms = statistics.median(theirs_times) * 1e3 if theirs_times else None
    return ours_ms, theirs_ms


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--iterations", type=int, default=20, help="iterations per batch")
    parser.add_argument("--repeats", type=int, default=10, help="batches of each library")
    args = parser.parse_args(argv)
    ours, theirs = anyio.run(run, args.iterations, args.repeats)
    loops = args.iterations * args.repeats
    print(f"sr2023 control loop, wire-timed simulators on ptys, median of {loops} loops:")
    print(f"  j5aio (4 boards at once)       {ours:8.2f} ms")
    if theirs is None:
        print("  sr-robot3                      not installed (pip install sr-robot3); skipped")
        return
    ratio = ours / theirs
    verdict = "met" if ratio <= GOAL else "NOT met"
    print(f"  sr-robot3 (one after another)  {theirs:8.2f} ms")
    print(f"  ratio j5aio / sr-robot3        {ratio:8.3f}   (goal <= {GOAL}: {verdict})")


if __name__ == "__main__":
    main()

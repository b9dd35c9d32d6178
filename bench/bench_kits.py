"""A robot's control loop on today's SR kit (sr2023): j5aio vs sr-robot3, wire-timed.

Each iteration of the loop touches all four serial boards of the kit, as a robot's loop
does: it reads the battery voltage (power board, fw 4.4), sets a motor's power (motor
board, fw 4.4), sets a servo's position (servo board, fw 4.3) and reads a digital pin
(SR Arduino, fw 2). Every board is a j5aio simulator served on a pseudo-terminal by a
process of its own, with ``--uart-timing``: each reply comes only after the time the
board's serial line takes to carry the request and the reply, as on the real wire.

* j5aio touches the four boards at once (:func:`j5aio.concurrency.at_once`, as the docs
  teach for requests whose answers a loop needs): the loop takes as long as the slowest
  board. For context, the same requests one task each in an ``asyncio.TaskGroup`` and in
  anyio's task group are printed beside it: anyio's group takes some 20 us longer to
  start its four tasks, all of it on the loop's critical path.
* j5aio's sync facade (a student's program) touches them one after another, as
  sr-robot3 does; the facade runs its calls with acknowledgements confirmed later (see
  the next item). j5aio's async API awaiting the same requests in turn, each waiting for
  its board's reply, is shown beside it.
* j5aio's async API awaiting them in turn inside
  :func:`~j5aio.backends.acknowledgements.acknowledge_later` (the path the sync facade
  takes with acknowledgements confirmed later): the motor's and the servo's ``ACK``
  travel while the next board's request does, and are read before each board's next
  request.
* sr-robot3 (Student Robotics' own library, from PyPI: ``pip install sr-robot3``, and
  ``opencv-python-headless`` for its vision import) does what its programs do, one
  board after another.

Each library has its own four simulators (a port is opened by one program at a time).
A simulator replies when its last byte would arrive on the real wire, to the
microsecond (:func:`j5aio.simulator.serve.reply_due`). On the wire alone, one iteration
is about 1.2 (power), 1.65 (motor), 1.8 (servo) and 0.35 ms (Arduino) at 115 200 baud
(:data:`WIRE_BYTES`): 4.95 ms one after another, 1.8 ms at once, so with no time added
by either library the ratio would be 0.37x. What each library adds per request decides
how far below or above that the ratio lands: below it only if sr-robot3's four
requests add more, in proportion, than j5aio's one wait for the slowest board. (The
power and servo boards are USB CDC devices, which ignore the baud rate; they are timed
as 115 200 baud lines here, as the motor board and the Arduino really are.)

Batches of iterations alternate between the two, so that drift affects both alike.
Printed: the median (p50) and p95 of each library's loop time, and the median over the
pairs of neighbouring batches of the ratio of their medians (the headline figure: robust
against the load of a shared machine changing during the run). Goals: j5aio's loop
<= 0.37x sr-robot3's; the sync facade's <= 0.95x sr-robot3's at p50 and <= 1.0x at p95.

Run: ``python bench/bench_kits.py [--iterations N] [--repeats R]`` (where sr-robot3 is
installed, e.g. the ``peers`` tox environment, or with its venv's site-packages on
``PYTHONPATH`` after j5aio's: ``PYTHONPATH=$PWD:/path/to/venv/lib/python3.11/site-packages``;
without it only j5aio is measured).
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import importlib
import importlib.util
import logging
import os
import statistics
import subprocess
import sys
import threading
import time
from collections.abc import Iterator
from typing import Any

import anyio

from j5aio.backends.acknowledgements import acknowledge_later
from j5aio.backends.hardware.sr.v4 import (
    SRArduinoHardwareBackend,
    SRV4MotorBoardFw4HardwareBackend,
    SRV4PowerBoardFw4HardwareBackend,
    SRV4ServoBoardFw4HardwareBackend,
)
from j5aio.boards.sr.v4 import MotorBoardFw4, PowerBoardFw4, ServoBoardFw4, SRArduinoBoard
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.concurrency import at_once

#: The simulators of the sr2023 kit's serial boards, by the role they play in the loop.
BOARDS = {
    "power": "sr-power-fw4",
    "motor": "sr-motor-fw4",
    "servo": "sr-servo-fw4",
    "arduino": "sr-arduino-fw2",
}
#: j5aio's loop over sr-robot3's: j5aio adds no more per request than sr-robot3 does
#: (the wire alone gives 0.368x).
GOAL = 0.37
#: The sync facade's loop (one board after another, as sr-robot3): p50 and p95 ratios.
SYNC_GOAL = 0.95
SYNC_P95_GOAL = 1.0
#: Each board's request and reply in one iteration of the loop, for the wire-time figures.
WIRE_BYTES = {
    "power": (b"BATT:V?\n", b"12000\n"),
    "motor": (b"MOT:0:SET:500\n", b"ACK\n"),
    "servo": (b"SERVO:0:SET:1750\n", b"ACK\n"),
    "arduino": (b"rd", b"l\n"),
}
SECONDS_PER_BYTE = 10 / 115_200


def wire_ms(role: str) -> float:
    """The time on a 115 200 baud wire of one board's request and reply, in ms."""
    request, reply = WIRE_BYTES[role]
    return (len(request) + len(reply)) * SECONDS_PER_BYTE * 1e3


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
        """The four requests at once with :func:`j5aio.concurrency.at_once`, as the docs teach."""
        power = 0.5 if index % 2 else -0.5
        await at_once(
            self.power.battery_sensor.get_voltage(),
            self.motor.motors[0].set_power(power),
            self.servo.servos[0].set_position(power),
            self.arduino.pins[3].digital_read(),
        )

    async def iteration_anyio_group(self, index: int) -> None:
        """The same requests at once, one task each in anyio's task group (context)."""
        power = 0.5 if index % 2 else -0.5
        async with anyio.create_task_group() as group:
            group.start_soon(self.power.battery_sensor.get_voltage)
            group.start_soon(self.motor.motors[0].set_power, power)
            group.start_soon(self.servo.servos[0].set_position, power)
            group.start_soon(self.arduino.pins[3].digital_read)

    async def iteration_asyncio_group(self, index: int) -> None:
        """The same requests at once in an ``asyncio.TaskGroup`` (context)."""
        power = 0.5 if index % 2 else -0.5
        async with asyncio.TaskGroup() as group:
            group.create_task(self.power.battery_sensor.get_voltage())
            group.create_task(self.motor.motors[0].set_power(power))
            group.create_task(self.servo.servos[0].set_position(power))
            group.create_task(self.arduino.pins[3].digital_read())

    async def iteration_in_turn(self, index: int) -> None:
        """The same requests awaited one after another, as the sync facade makes them."""
        power = 0.5 if index % 2 else -0.5
        await self.power.battery_sensor.get_voltage()
        await self.motor.motors[0].set_power(power)
        await self.servo.servos[0].set_position(power)
        await self.arduino.pins[3].digital_read()

    async def batch(
        self,
        iterations: int,
        *,
        in_turn: bool = False,
        ack_later: bool = False,
        asyncio_group: bool = False,
        anyio_group: bool = False,
    ) -> list[float]:
        """Time ``iterations`` loops: at once (with ``at_once``, or in anyio's or asyncio's
        task group), or in turn (with acknowledgements later)."""
        if in_turn:
            iteration = self.iteration_in_turn
        elif asyncio_group:
            iteration = self.iteration_asyncio_group
        elif anyio_group:
            iteration = self.iteration_anyio_group
        else:
            iteration = self.iteration
        times = []
        with acknowledge_later(ack_later):
            for index in range(iterations):
                start = time.perf_counter()
                await iteration(index)
                times.append(time.perf_counter() - start)
            if ack_later:  # what is still owed is read before the next batch's timing
                for board in (self.power, self.motor, self.servo, self.arduino):
                    await board.backend.link.confirm()  # type: ignore[attr-defined]
        return times

    async def close(self) -> None:
        for board in (self.power, self.motor, self.servo, self.arduino):
            await board.close()


class J5aioSyncLoop:
    """The loop through j5aio's sync facade, as a student writes it: one board after another."""

    def __init__(self, paths: dict[str, str]) -> None:
        from j5aio.sync import wrapping

        backends: dict[str, Any] = {
            "power": SRV4PowerBoardFw4HardwareBackend,
            "motor": SRV4MotorBoardFw4HardwareBackend,
            "servo": SRV4ServoBoardFw4HardwareBackend,
            "arduino": SRArduinoHardwareBackend,
        }
        self.cores: list[Any] = []
        boards: dict[str, Any] = {}
        for role, backend in backends.items():
            core = wrapping.call(backend.attach, paths[role])
            wrapping.call(core.setup)
            self.cores.append(core)
            boards[role] = wrapping.wrap(core)
        self.power, self.motor = boards["power"], boards["motor"]
        self.servo, self.arduino = boards["servo"], boards["arduino"]
        self.arduino.pins[3].mode = GPIOPinMode.DIGITAL_INPUT

    def iteration(self, index: int) -> None:
        power = 0.5 if index % 2 else -0.5
        self.power.battery_sensor.voltage  # noqa: B018 - a read over the wire
        self.motor.motors[0].power = power
        self.servo.servos[0].position = power
        self.arduino.pins[3].digital_read()

    def batch(self, iterations: int) -> list[float]:
        # A student's program calls the facade from a thread with no event loop running in
        # it, so that the call runs the facade's loop itself; this bench's own thread runs
        # a loop, so the batch runs in a plain thread (this one waits, as it did before).
        times: list[float] = []
        student = threading.Thread(target=self._batch, args=(iterations, times))
        student.start()
        student.join()
        return times

    def _batch(self, iterations: int, times: list[float]) -> None:
        for index in range(iterations):
            start = time.perf_counter()
            self.iteration(index)
            times.append(time.perf_counter() - start)

    def close(self) -> None:
        from j5aio.sync import wrapping

        for core in self.cores:
            wrapping.call(core.close)


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


class Figures:
    """Loop times of each library, batch by batch, in seconds."""

    def __init__(self) -> None:
        self.ours: list[list[float]] = []
        self.ours_sync: list[list[float]] = []
        self.ours_asyncio_group: list[list[float]] = []
        self.ours_anyio_group: list[list[float]] = []
        self.ours_in_turn: list[list[float]] = []
        self.ours_ack_later: list[list[float]] = []
        self.theirs: list[list[float]] = []

    @staticmethod
    def p50_p95_ms(batches: list[list[float]]) -> tuple[float, float]:
        """The median and p95 of every loop of ``batches``, in ms."""
        loops = [time for batch in batches for time in batch]
        return (
            statistics.median(loops) * 1e3,
            statistics.quantiles(loops, n=20, method="inclusive")[18] * 1e3,
        )

    def paired_ratio(self, ours_batches: list[list[float]] | None = None) -> float:
        """The median over neighbouring batches of (j5aio's median / sr-robot3's median).

        ``ours_batches`` are j5aio's async batches unless given (the sync facade's).
        """
        return statistics.median(
            statistics.median(ours) / statistics.median(theirs)
            for ours, theirs in zip(
                self.ours if ours_batches is None else ours_batches, self.theirs, strict=True,
            )
        )


async def run(iterations: int, repeats: int) -> Figures:
    """Measure interleaved batches of j5aio and sr-robot3 (if installed)."""
    have_peer = importlib.util.find_spec("sr") is not None and (
        importlib.util.find_spec("sr.robot3") is not None
    )
    with contextlib.ExitStack() as stack:
        ours_paths = stack.enter_context(served_kit("J5AIO"))
        sync_paths = stack.enter_context(served_kit("J5SYNC"))
        theirs_paths = stack.enter_context(served_kit("SRR3")) if have_peer else None
        ours = await J5aioLoop.attach(ours_paths)
        # The sync facade blocks this thread (this loop has nothing else to do meanwhile),
        # as it blocks a student's main thread.
        ours_sync = J5aioSyncLoop(sync_paths)
        theirs = SRRobot3Loop(theirs_paths) if theirs_paths is not None else None
        figures = Figures()
        await ours.batch(5)  # warm up
        ours_sync.batch(5)
        if theirs is not None:
            theirs.batch(5)
        for index in range(repeats):  # interleaved batches, alternating who goes first
            if theirs is not None and index % 2:
                figures.theirs.append(theirs.batch(iterations))
            figures.ours.append(await ours.batch(iterations))
            figures.ours_sync.append(ours_sync.batch(iterations))
            figures.ours_asyncio_group.append(await ours.batch(iterations, asyncio_group=True))
            figures.ours_anyio_group.append(await ours.batch(iterations, anyio_group=True))
            figures.ours_in_turn.append(await ours.batch(iterations, in_turn=True))
            figures.ours_ack_later.append(
                await ours.batch(iterations, in_turn=True, ack_later=True)
            )
            if theirs is not None and not index % 2:
                figures.theirs.append(theirs.batch(iterations))
        await ours.close()
        ours_sync.close()
    # sr-robot3 resets its boards at exit, after their simulators have gone: quiet.
    logging.getLogger("sr.robot3").setLevel(logging.CRITICAL)
    return figures


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--iterations", type=int, default=20, help="iterations per batch")
    parser.add_argument("--repeats", type=int, default=10, help="batches of each library")
    args = parser.parse_args(argv)
    figures = anyio.run(run, args.iterations, args.repeats)
    loops = args.iterations * args.repeats
    wire = {role: wire_ms(role) for role in WIRE_BYTES}
    at_once, in_turn = max(wire.values()), sum(wire.values())
    print(
        f"sr2023 control loop, wire-timed simulators on ptys, {loops} loops of each library "
        f"(load {os.getloadavg()[0]:.1f} on {os.cpu_count()} CPUs):"
    )
    print(
        f"  on the wire alone: {in_turn:.2f} ms one board after another, {at_once:.2f} ms "
        f"at once: {at_once / in_turn:.3f}x"
    )
    print("                                    p50        p95")
    ours50, ours95 = figures.p50_p95_ms(figures.ours)
    print(f"  j5aio (4 boards at once)       {ours50:8.2f}   {ours95:8.2f} ms"
          "   (at_once)")
    sync50, sync95 = figures.p50_p95_ms(figures.ours_sync)
    print(f"  j5aio sync (one after another) {sync50:8.2f}   {sync95:8.2f} ms"
          "   (the facade confirms acknowledgements later)")
    group50, group95 = figures.p50_p95_ms(figures.ours_asyncio_group)
    print(f"  at once, asyncio.TaskGroup     {group50:8.2f}   {group95:8.2f} ms"
          "   (context: the same requests, one task each in asyncio's task group)")
    anyio50, anyio95 = figures.p50_p95_ms(figures.ours_anyio_group)
    print(f"  at once, anyio task group      {anyio50:8.2f}   {anyio95:8.2f} ms"
          "   (context: the same in anyio's task group, ~20 us more to start its tasks)")
    turn50, turn95 = figures.p50_p95_ms(figures.ours_in_turn)
    print(f"  j5aio async, awaited in turn   {turn50:8.2f}   {turn95:8.2f} ms"
          "   (the sync loop's requests with no thread hand-off)")
    later50, later95 = figures.p50_p95_ms(figures.ours_ack_later)
    print(f"  in turn, ACKs confirmed later  {later50:8.2f}   {later95:8.2f} ms"
          "   (the same, inside acknowledge_later(), as the sync facade runs its calls)")
    if not figures.theirs:
        print("  sr-robot3                      not installed (pip install sr-robot3); skipped")
        return
    theirs50, theirs95 = figures.p50_p95_ms(figures.theirs)
    print(f"  sr-robot3 (one after another)  {theirs50:8.2f}   {theirs95:8.2f} ms")
    print(f"  ratio of the p50s              {ours50 / theirs50:8.3f}")
    ratio = figures.paired_ratio()
    verdict = "met" if ratio <= GOAL else "NOT met"
    print(
        f"  ratio j5aio / sr-robot3, median over {len(figures.ours)} neighbouring batches "
        f"{ratio:.3f}   (goal <= {GOAL}: {verdict})"
    )
    for label, batches, p95 in (
        ("at once, asyncio.TaskGroup", figures.ours_asyncio_group, group95),
        ("at once, anyio task group", figures.ours_anyio_group, anyio95),
        ("async in turn", figures.ours_in_turn, turn95),
        ("in turn, ACKs later", figures.ours_ack_later, later95),
    ):
        print(
            f"  {label}: j5aio / sr-robot3 median over neighbouring batches "
            f"{figures.paired_ratio(batches):.3f}, ratio of the p95s {p95 / theirs95:.3f}"
        )
    sync_ratio = figures.paired_ratio(figures.ours_sync)
    sync_verdict = "met" if sync_ratio <= SYNC_GOAL and sync95 <= theirs95 * SYNC_P95_GOAL else (
        "NOT met"
    )
    print(
        f"  sync facade: ratio of the p95s {sync95 / theirs95:.3f}, j5aio sync / sr-robot3 "
        f"median over neighbouring batches {sync_ratio:.3f}   (goals <= {SYNC_GOAL}, "
        f"p95 <= {SYNC_P95_GOAL}: {sync_verdict})"
    )


if __name__ == "__main__":
    main()

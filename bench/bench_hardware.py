"""Speed of the hardware backends, against simulated boards on real pseudo-terminals.

Each simulated board is served on a pty by a separate process (``python -m j5aio simulate
sb-arduino --pty``), so the server never competes with the measured code for the GIL.
Every figure is a median, and the things compared are measured side by side in one run:

(a) one request (``R 2`` → ``# R 2`` / ``> L`` / ``+ OK``) through the j5aio SB Arduino
    backend vs the same bytes through raw blocking pyserial: the median (p50) and the tail
    (p95) of the round trip, on an instant simulator and on a wire-timed one (a 115200 baud
    board, ``--uart-timing``), each figure the median over the repeats of that repeat's
    percentile (goals: p50 <= 1.05x, p95 <= 1.1x raw);
(b) four boards queried at once (one task each, four ptys) vs one board alone, the
    same number of requests per board (goal: <= 1.15x the time of one);
(c) a request sequence (write a pin, read a pin, read an analogue pin) through j5 0.12
    vs j5aio (ratio reported). j5 0.12 runs in a child process of its own virtual
    environment, made from the package registry on first use (``bench/_peers.py``); its
    backend is constructed with the pty's path.

Run: ``python bench/bench_hardware.py [--requests N] [--repeats R] [--round-trip-only]``
"""

from __future__ import annotations

import argparse
import contextlib
import functools
import os
import statistics
import subprocess
import sys
import threading
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import anyio
import serial
from _peers import J5_PEER, peer_python  # type: ignore[import-not-found]

from j5aio.backends.hardware.sb import SBArduinoHardwareBackend
from j5aio.components.gpio_pin import GPIOPinMode

BENCH_DIR = Path(__file__).resolve().parent
SERVER_TIME_SCALE = "0.05"  # the simulated Arduino boots in 75 ms instead of 1.5 s


@contextlib.contextmanager
def served_boards(count: int, *, uart_timing: bool = False) -> Iterator[list[str]]:
    """Serve ``count`` simulated SB Arduinos on ptys, each from its own process.

    With ``uart_timing`` each reply is held back for the time the board's 115200 baud
    serial line would take to carry the request and the reply, as on real hardware.
    """
    processes = []
    try:
        paths = []
        for index in range(count):
            process = subprocess.Popen(
                [
                    sys.executable,
                    "-m",
                    "j5aio",
                    "simulate",
                    "sb-arduino",
                    "--pty",
                    "--time-scale",
                    SERVER_TIME_SCALE,
                    "--serial-number",
                    f"BENCH{index}",
                    *(["--uart-timing"] if uart_timing else []),
                ],
                stdout=subprocess.PIPE,
                stderr=subprocess.DEVNULL,
                text=True,
            )
            processes.append(process)
            assert process.stdout is not None
            paths.append(process.stdout.readline().strip())
        yield paths
    finally:
        for process in processes:
            process.terminate()
        for process in processes:
            process.wait(5)


def median_us(samples: list[float]) -> float:
    return statistics.median(samples) * 1e6


# -- (a) one round trip --------------------------------------------------------------------


def raw_pyserial_round_trips(path: str, requests: int) -> list[float]:
    port = serial.Serial(path, 115200, timeout=2)
    try:
        banner = port.readline()
        assert banner == b"# Booted\n", banner
        port.readline()  # the version line
        times = []
        for _ in range(requests):
            start = time.perf_counter()
            port.write(b"R 2\n")
            while True:
                line = port.readline()
                if line[:1] in (b"+", b"-"):
                    break
                assert line, "timed out"
            times.append(time.perf_counter() - start)
        return times
    finally:
        port.close()


async def j5aio_round_trips(path: str, requests: int) -> list[float]:
    board = await SBArduinoHardwareBackend.attach(path)
    backend = board.backend
    assert isinstance(backend, SBArduinoHardwareBackend)
    try:
        times = []
        for _ in range(requests):
            start = time.perf_counter()
            await backend.read_gpio_pin_digital_state(2)
            times.append(time.perf_counter() - start)
        return times
    finally:
        await board.close()


def percentiles_us(samples: list[float]) -> tuple[float, float]:
    """The p50 and p95 of ``samples`` (seconds), in microseconds."""
    cuts = statistics.quantiles(samples, n=20, method="inclusive")
    return statistics.median(samples) * 1e6, cuts[18] * 1e6


class RoundTrips:
    """p50 and p95 of each repeat, for raw pyserial and for j5aio."""

    def __init__(self) -> None:
        self.raw: list[tuple[float, float]] = []
        self.ours: list[tuple[float, float]] = []

    def figure(self, side: str, which: int) -> float:
        """The median over the repeats of p50 (``which`` 0) or p95 (1), in microseconds."""
        items: list[tuple[float, float]] = self.raw if side == "raw" else self.ours
        return statistics.median(item[which] for item in items)


def bench_round_trip(path: str, requests: int, repeats: int) -> RoundTrips:
    trips = RoundTrips()
    for index in range(repeats):  # interleaved, and alternating who goes first
        for side in ("raw", "ours") if index % 2 == 0 else ("ours", "raw"):
            if side == "raw":
                times = raw_pyserial_round_trips(path, requests)
            else:
                times = anyio.run(j5aio_round_trips, path, requests)
            (trips.raw if side == "raw" else trips.ours).append(percentiles_us(times))
            time.sleep(0.05)  # let the pty server see the port close before it reopens
    return trips


def report_round_trips(title: str, trips: RoundTrips) -> None:
    raw50, raw95 = trips.figure("raw", 0), trips.figure("raw", 1)
    ours50, ours95 = trips.figure("ours", 0), trips.figure("ours", 1)
    report(
        title,
        [
            ("raw pyserial (blocking)  p50 / p95", f"{raw50:8.1f} / {raw95:8.1f} us"),
            ("j5aio SB Arduino backend p50 / p95", f"{ours50:8.1f} / {ours95:8.1f} us"),
            ("j5aio / raw, p50", f"{ours50 / raw50:8.3f}   (goal <= 1.05: "
             f"{'met' if ours50 / raw50 <= 1.05 else 'NOT met'})"),
        ],
        f"j5aio / raw, p95 {ours95 / raw95:.3f}   (goal <= 1.1: "
        f"{'met' if ours95 / raw95 <= 1.1 else 'NOT met'})",
    )


# -- (b) four boards at once ----------------------------------------------------------------


async def boards_at_once(paths: list[str], requests: int, *, sequential: bool = False) -> float:
    """Time ``requests`` reads on each board: one task per board, or one board after another."""
    boards = [await SBArduinoHardwareBackend.attach(path) for path in paths]
    try:

        async def query(board: Any) -> None:
            for _ in range(requests):
                await board.backend.read_gpio_pin_digital_state(2)

        start = time.perf_counter()
        if sequential:
            for board in boards:
                await query(board)
        else:
            async with anyio.create_task_group() as group:
                for board in boards:
                    group.start_soon(query, board)
        return time.perf_counter() - start
    finally:
        for board in boards:
            await board.close()


def bench_wire_timed(paths: list[str], requests: int, repeats: int) -> tuple[float, float, float]:
    """Medians (ms) of one board, four at once and four in sequence, on wire-timed boards."""
    one: list[float] = []
    four: list[float] = []
    in_sequence: list[float] = []
    for _ in range(repeats):
        one.append(anyio.run(boards_at_once, paths[:1], requests))
        time.sleep(0.05)
        four.append(anyio.run(boards_at_once, paths, requests))
        time.sleep(0.05)
        in_sequence.append(
            anyio.run(functools.partial(boards_at_once, paths, requests, sequential=True)),
        )
        time.sleep(0.05)
    return tuple(statistics.median(x) * 1e3 for x in (one, four, in_sequence))  # type: ignore[return-value]


def raw_threads_at_once(paths: list[str], requests: int) -> float:
    """The control: raw pyserial, one thread per board (what the machine itself allows)."""
    barrier = threading.Barrier(len(paths) + 1)
    results: list[float] = []

    def run(path: str) -> None:
        port = serial.Serial(path, 115200, timeout=2)
        try:
            port.readline()
            port.readline()
            barrier.wait()
            for _ in range(requests):
                port.write(b"R 2\n")
                while port.readline()[:1] not in (b"+", b"-"):
                    pass
        finally:
            port.close()
            results.append(time.perf_counter())

    threads = [threading.Thread(target=run, args=(path,)) for path in paths]
    for thread in threads:
        thread.start()
    barrier.wait()
    start = time.perf_counter()
    for thread in threads:
        thread.join()
    return max(results) - start


def bench_concurrency(
    paths: list[str], requests: int, repeats: int
) -> tuple[float, float, float, float]:
    one: list[float] = []
    four: list[float] = []
    raw_one: list[float] = []
    raw_four: list[float] = []
    for _ in range(repeats):
        one.append(anyio.run(boards_at_once, paths[:1], requests))
        time.sleep(0.05)
        four.append(anyio.run(boards_at_once, paths, requests))
        time.sleep(0.05)
        raw_one.append(raw_threads_at_once(paths[:1], requests))
        time.sleep(0.05)
        raw_four.append(raw_threads_at_once(paths, requests))
        time.sleep(0.05)
    return tuple(statistics.median(x) * 1e3 for x in (one, four, raw_one, raw_four))  # type: ignore[return-value]


# -- (c) j5 0.12 ----------------------------------------------------------------------------


#: j5's side of (c), run by j5 0.12's own interpreter (bench/_peers.py): argv is the pty's
#: path and the number of rounds; it prints one time per round, in seconds.
J5_SEQUENCE = """
import sys, time
from j5.backends.hardware.sb.arduino import SBArduinoHardwareBackend
from j5.components import GPIOPinMode
path, rounds = sys.argv[1], int(sys.argv[2])
backend = SBArduinoHardwareBackend(path)  # the least invasive way: it takes a path
backend.set_gpio_pin_mode(3, GPIOPinMode.DIGITAL_OUTPUT)
try:
    for index in range(rounds):
        start = time.perf_counter()
        backend.write_gpio_pin_digital_state(3, index % 2 == 0)
        backend.read_gpio_pin_digital_state(2)
        backend.read_gpio_pin_analogue_value(14)
        print(time.perf_counter() - start)
finally:
    backend._serial.close()
"""


def sequence_j5(j5_python: Path, path: str, rounds: int) -> list[float]:
    """Run the sequence through j5 0.12 in its own interpreter; the time of each round."""
    result = subprocess.run(
        [str(j5_python), "-c", J5_SEQUENCE, path, str(rounds)],
        capture_output=True,
        text=True,
        check=False,
    )
    if result.returncode != 0:
        raise RuntimeError(f"j5 0.12's sequence failed:\n{result.stderr.strip()}")
    return [float(line) for line in result.stdout.split()]


async def sequence_j5aio(path: str, rounds: int) -> list[float]:
    board = await SBArduinoHardwareBackend.attach(path)
    backend = board.backend
    assert isinstance(backend, SBArduinoHardwareBackend)
    await backend.set_gpio_pin_mode(3, GPIOPinMode.DIGITAL_OUTPUT)
    times = []
    try:
        for index in range(rounds):
            start = time.perf_counter()
            await backend.write_gpio_pin_digital_state(3, index % 2 == 0)
            await backend.read_gpio_pin_digital_state(2)
            await backend.read_gpio_pin_analogue_value(14)
            times.append(time.perf_counter() - start)
        return times
    finally:
        await board.close()


def bench_j5(path: str, rounds: int, repeats: int) -> tuple[float, float]:
    j5_python = peer_python(*J5_PEER)
    theirs: list[float] = []
    ours: list[float] = []
    for _ in range(repeats):
        theirs += sequence_j5(j5_python, path, rounds)
        time.sleep(0.05)
        ours += anyio.run(sequence_j5aio, path, rounds)
        time.sleep(0.05)
    return median_us(theirs), median_us(ours)


def report(title: str, figures: list[tuple[str, str]], verdict: str) -> None:
    print(title)
    for name, value in figures:
        print(f"    {name:<44} {value}")
    print(f"    {verdict}")


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--requests", type=int, default=500, help="requests per measurement")
    parser.add_argument("--repeats", type=int, default=5, help="measurements per figure")
    parser.add_argument(
        "--round-trip-only", action="store_true", help="measure (a) only, instant and wire-timed"
    )
    args = parser.parse_args(argv)

    def goal(ratio: float, limit: float) -> str:
        return f"ratio {ratio:.3f} (goal <= {limit}: {'met' if ratio <= limit else 'NOT met'})"

    print(
        f"Python {sys.version.split()[0]}; {os.cpu_count()} CPUs; load {os.getloadavg()[0]:.1f}; "
        f"{args.requests} requests x {args.repeats} repeats; simulated SB Arduinos on ptys, "
        "one server process each\n"
    )
    with served_boards(1, uart_timing=True) as paths:
        report_round_trips(
            "(a) one round trip on a wire-timed board (115200 baud), medians over repeats",
            bench_round_trip(paths[0], args.requests, args.repeats),
        )
    with served_boards(4) as paths:
        report_round_trips(
            "(a') one round trip on an instant board, medians over repeats",
            bench_round_trip(paths[0], args.requests, args.repeats),
        )
        if args.round_trip_only:
            return
        one, four, raw_one, raw_four = bench_concurrency(paths, args.requests, args.repeats)
        report(
            f"(b) {args.requests} requests per board, wall time, median",
            [
                ("j5aio, one board", f"{one:8.1f} ms"),
                ("j5aio, four boards at once (one task each)", f"{four:8.1f} ms"),
                ("control: raw pyserial, one thread", f"{raw_one:8.1f} ms"),
                ("control: raw pyserial, four threads", f"{raw_four:8.1f} ms"),
                ("control ratio (what this machine allows)", f"{raw_four / raw_one:8.3f}"),
            ],
            goal(four / one, 1.15) + "  [instant simulators: CPU-bound on this machine]",
        )
        theirs, ours = bench_j5(paths[1], args.requests // 5, args.repeats)
        report(
            "(c) sequence: write pin, read pin, read analogue; median",
            [("j5 0.12 (blocking pyserial)", f"{theirs:8.1f} us"), ("j5aio", f"{ours:8.1f} us")],
            f"j5aio / j5 0.12 = {ours / theirs:.3f}",
        )
    wire_requests = max(1, args.requests // 5)
    with served_boards(4, uart_timing=True) as paths:
        one, four, in_sequence = bench_wire_timed(paths, wire_requests, args.repeats)
        report(
            f"(b') {wire_requests} requests per board on wire-timed simulators "
            "(115200 baud, as the real boards), wall time, median",
            [
                ("j5aio, one board", f"{one:8.1f} ms"),
                ("j5aio, four boards at once (one task each)", f"{four:8.1f} ms"),
                ("j5aio, four boards one after another (as j5)", f"{in_sequence:8.1f} ms"),
                ("one after another / one board", f"{in_sequence / one:8.3f}"),
            ],
            goal(four / one, 1.15),
        )


if __name__ == "__main__":
    main()

"""How much a sync facade call costs on top of awaiting the same coroutine.

Measures, in one run, the median and mean time of:

* a direct ``await`` inside an event loop (the floor);
* the facade: a blocking call of ``j5aio.sync``, whose calling thread runs the event loop
  itself (no thread hand-off);
* anyio's stock blocking portal (``portal.call``), for reference;
* the machine's floor for a thread portal built on asyncio's own wake-up: waking an event
  loop in another thread (``call_soon_threadsafe``) and being woken back by a lock, with
  no coroutine at all; and the floor for any two-thread hand-off, a lock each way (two
  futex wake-ups, which is what j5aio's former portal, now its fallback, pays);
* (simulated case only) the floor of a facade with no hand-off at all: the calling thread
  runs a loop of its own until its coroutine is done (``loop.run_until_complete``);

for a no-op coroutine, for a console backend call (``motor.get_power()`` on the SR v4
motor board's console backend, which answers from memory without printing), and for
the case measured: ``motor.power = 0.5`` on a simulated SR motor board (the hardware backend
and its codec over an in-memory simulator stream), against ``await motor.set_power(0.5)``.
The rounds of the ways are interleaved so that machine noise hits them alike.

It then times a call made after the program has been away from calls for longer than the
keeper's grace (the keeper runs the loop then, and the call takes it back), checks the
facade at rest: the CPU used and the context switches made by the
waiting thread (and the CPU of the whole process) while a facade call waits 0.2 s and
2 s with no board, and how long a Ctrl-C takes to stop a waiting call, sent to the
process (as a terminal does) and sent to another thread of the program. Run::

    python bench/bench_sync_facade.py [--calls 10000] [--rounds 5] [--interrupts 10]

Goals: at most 15 µs overhead per facade call over a direct await, median and
mean, for the simulated ``motor.power = 0.5``, on a quiet and on a busy machine alike
(two ``python -c 'while 1: pass'`` beside it on this 2-core machine); no periodic
wake-up while waiting, and a Ctrl-C that stops a waiting call within 50 ms. Read the
facade's figure against the caller-driven floor measured in the same run: the facade
runs the loop in the caller's thread like it, so it can cost no less.
"""

from __future__ import annotations

import argparse
import asyncio
import os
import signal
import statistics
import threading
import time
from collections.abc import Awaitable, Callable
from pathlib import Path
from typing import Any

import anyio
from anyio.from_thread import start_blocking_portal

from j5aio.backends.console.sr.v4 import SRV4MotorBoardConsoleBackend
from j5aio.backends.hardware.sr.v4 import SRV4MotorBoardHardwareBackend
from j5aio.backends.hardware.transports.memory import SimulatorStream
from j5aio.boards.sr.v4 import MotorBoard
from j5aio.components.motor import Motor
from j5aio.simulator import SRMotorBoardFw3Simulator
from j5aio.sync import MotorBoard as SyncMotorBoard
from j5aio.sync import shutdown
from j5aio.sync._runtime import call
from j5aio.sync.wrapping import wrap

GOAL_US = 15.0
PAUSE = 0.03  # longer than the keeper's grace
CTRL_C_GOAL_MS = 50.0
IDLE_SECONDS = 2.0
SIMULATED = "simulated motor.power = 0.5"


async def noop() -> None:
    """Do nothing: the cost of the call machinery alone."""


def time_direct(fn: Callable[[], Awaitable[Any]], calls: int) -> list[float]:
    async def run() -> list[float]:
        samples = []
        for _ in range(calls):
            start = time.perf_counter()
            await fn()
            samples.append(time.perf_counter() - start)
        return samples

    return asyncio.run(run())


async def simulated_motor() -> Motor:
    """A motor of a simulated SR motor board, opened in the running loop."""
    stream = SimulatorStream(SRMotorBoardFw3Simulator("BENCH"), name="bench", time_scale=0)
    board = await SRV4MotorBoardHardwareBackend.from_stream(
        stream, port="bench", serial_number="BENCH", time_scale=0
    )
    assert isinstance(board, MotorBoard)
    return board.motors[0]


def time_direct_simulated(calls: int) -> list[float]:
    async def run() -> list[float]:
        motor = await simulated_motor()
        samples = []
        for _ in range(calls):
            start = time.perf_counter()
            await motor.set_power(0.5)
            samples.append(time.perf_counter() - start)
        await motor.set_power(0)
        return samples

    return asyncio.run(run())


def time_caller_driven_simulated(loop: asyncio.AbstractEventLoop, calls: int) -> list[float]:
    """Time ``motor.set_power(0.5)`` run by the calling thread driving ``loop`` itself.

    The floor of a facade with no thread hand-off: each blocking call runs the event loop
    in the caller's thread until its coroutine is done (``run_until_complete``).
    """
    motor = loop.run_until_complete(simulated_motor())
    samples = []
    for _ in range(calls):
        start = time.perf_counter()
        loop.run_until_complete(motor.set_power(0.5))
        samples.append(time.perf_counter() - start)
    loop.run_until_complete(motor.set_power(0))
    return samples


def time_blocking(fn: Callable[[], Any], calls: int) -> list[float]:
    samples = []
    for _ in range(calls):
        start = time.perf_counter()
        fn()
        samples.append(time.perf_counter() - start)
    return samples


def time_handoff(loop: asyncio.AbstractEventLoop, calls: int) -> list[float]:
    """Time a bare round trip to a loop thread: wake it, and be woken back by a lock."""
    samples = []
    for _ in range(calls):
        start = time.perf_counter()
        done = threading.Lock()
        done.acquire()
        loop.call_soon_threadsafe(done.release)
        done.acquire()
        samples.append(time.perf_counter() - start)
    return samples


def time_futex_pair(calls: int) -> list[float]:
    """Time the floor of any two-thread hand-off: a lock released each way."""
    there, back = threading.Lock(), threading.Lock()
    there.acquire()
    back.acquire()
    stop = False

    def serve() -> None:
        while True:
            there.acquire()
            if stop:
                return
            back.release()

    server = threading.Thread(target=serve, daemon=True)
    server.start()
    samples = []
    for _ in range(calls):
        start = time.perf_counter()
        there.release()
        back.acquire()
        samples.append(time.perf_counter() - start)
    stop = True
    there.release()
    server.join()
    return samples


def context_switches() -> int | None:
    """Return the context switches this thread has made so far, if Linux says."""
    try:
        status = Path("/proc/thread-self/status").read_text()
    except OSError:
        return None
    return sum(
        int(line.split()[1])
        for line in status.splitlines()
        if line.startswith(("voluntary_ctxt_switches", "nonvoluntary_ctxt_switches"))
    )


def measure_idle() -> None:
    """Print what a facade call waiting with no board costs the waiting thread and process.

    A wait of IDLE_SECONDS is compared with one a tenth as long: a thread that polls
    makes more context switches the longer it waits; one that sleeps until woken does not.
    """
    call(noop)  # the portal is up
    print("\nidle: one facade call waiting, no board")
    for seconds in (IDLE_SECONDS / 10, IDLE_SECONDS):
        switches = context_switches()
        thread_cpu, process_cpu, wall = time.thread_time(), time.process_time(), time.monotonic()
        call(anyio.sleep, seconds)
        wall = time.monotonic() - wall
        thread_cpu = time.thread_time() - thread_cpu
        process_cpu = time.process_time() - process_cpu
        after = context_switches()
        counted = "" if switches is None or after is None else f", {after - switches} switches"
        print(
            f"  {seconds:4.1f} s: waiting thread {thread_cpu * 1e3:6.3f} ms CPU "
            f"({100 * thread_cpu / wall:.4f} %){counted}; "
            f"whole process {process_cpu * 1e3:6.3f} ms CPU ({100 * process_cpu / wall:.4f} %)"
        )


def measure_after_pause(calls: int) -> None:
    """Print what a call costs after the program was away from calls for :data:`PAUSE`."""
    samples = []
    for _ in range(calls):
        time.sleep(PAUSE)  # the keeper takes the loop meanwhile
        start = time.perf_counter()
        call(noop)
        samples.append(time.perf_counter() - start)
    print(
        f"\nno-op call after {PAUSE * 1e3:.0f} ms away from calls (taken back from the keeper), "
        f"{calls} calls: median {statistics.median(samples) * 1e6:.1f} us, "
        f"mean {statistics.fmean(samples) * 1e6:.1f} us"
    )


def measure_ctrl_c(times: int) -> None:
    """Print how long a Ctrl-C takes to stop a waiting facade call (until it re-raises)."""
    def to_the_process() -> None:
        os.kill(os.getpid(), signal.SIGINT)

    def to_another_thread() -> None:
        signal.pthread_kill(threading.get_ident(), signal.SIGINT)

    print(f"\nCtrl-C while a facade call waits (goal {CTRL_C_GOAL_MS:.0f} ms), {times} times")
    for label, send in (
        ("to the process, as a terminal sends it", to_the_process),
        ("landing on another thread of the program", to_another_thread),
    ):
        latencies = []
        for _ in range(times):
            sent: list[float] = []

            def interrupt(send: Callable[[], None] = send, sent: list[float] = sent) -> None:
                sent.append(time.perf_counter())
                send()

            timer = threading.Timer(0.05, interrupt)
            timer.start()
            try:
                call(anyio.sleep, 10)
            except KeyboardInterrupt:
                latencies.append(time.perf_counter() - sent[0])
            timer.join()
        if len(latencies) < times:
            print(f"  {label}: NOT STOPPED in {times - len(latencies)} of {times}")
            continue
        worst = max(latencies) * 1e3
        verdict = "meets" if worst <= CTRL_C_GOAL_MS else "MISSES"
        print(
            f"  {label:<42} median {statistics.median(latencies) * 1e3:6.2f} ms, "
            f"worst {worst:6.2f} ms ({verdict} the goal)"
        )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--calls", type=int, default=10000, help="calls per round")
    parser.add_argument("--rounds", type=int, default=5, help="interleaved rounds")
    parser.add_argument("--interrupts", type=int, default=10, help="Ctrl-Cs per way")
    options = parser.parse_args()

    core_board = MotorBoard("BENCH", SRV4MotorBoardConsoleBackend("BENCH"))
    motor = core_board.motors[0]
    sync_board = wrap(core_board)
    assert isinstance(sync_board, SyncMotorBoard)
    sync_motor = sync_board.motors[0]
    sync_simulated = wrap(call(simulated_motor))

    def set_simulated() -> None:
        sync_simulated.power = 0.5

    samples: dict[tuple[str, str], list[float]] = {}

    def add(case: str, way: str, values: list[float]) -> None:
        samples.setdefault((case, way), []).extend(values)

    driven_loop = asyncio.new_event_loop()
    handoff_loop = asyncio.new_event_loop()
    handoff_thread = threading.Thread(target=handoff_loop.run_forever, daemon=True)
    handoff_thread.start()
    with start_blocking_portal() as portal:
        for _ in range(options.rounds):
            n = options.calls
            add("thread hand-off", "bare wake-up and back", time_handoff(handoff_loop, n))
            add("thread hand-off", "a lock each way", time_futex_pair(n))
            add("no-op coroutine", "direct await", time_direct(noop, n))
            add("no-op coroutine", "j5aio.sync call", time_blocking(lambda: call(noop), n))
            add("no-op coroutine", "anyio portal.call", time_blocking(lambda: portal.call(noop), n))
            add("console motor.get_power()", "direct await", time_direct(motor.get_power, n))
            add(
                "console motor.get_power()",
                "j5aio.sync facade (motor.power)",
                time_blocking(lambda: sync_motor.power, n),
            )
            add(
                "console motor.get_power()",
                "anyio portal.call",
                time_blocking(lambda: portal.call(motor.get_power), n),
            )
            add(SIMULATED, "direct await", time_direct_simulated(n))
            add(SIMULATED, "j5aio.sync facade", time_blocking(set_simulated, n))
            add(
                SIMULATED,
                "caller drives the loop (no hand-off)",
                time_caller_driven_simulated(driven_loop, n),
            )
    handoff_loop.call_soon_threadsafe(handoff_loop.stop)
    handoff_thread.join()
    driven_loop.close()

    print(f"{options.rounds} rounds x {options.calls} calls; microseconds\n")
    print(f"{'case':<28} {'way':<34} {'median':>8} {'mean':>8} {'overhead':>9} {'(mean)':>8}")
    cases = ("no-op coroutine", "console motor.get_power()", SIMULATED)
    for case in cases:
        floor = statistics.median(samples[(case, "direct await")]) * 1e6
        floor_mean = statistics.fmean(samples[(case, "direct await")]) * 1e6
        for (this_case, way), values in samples.items():
            if this_case != case:
                continue
            median = statistics.median(values) * 1e6
            mean = statistics.fmean(values) * 1e6
            print(
                f"{case:<28} {way:<34} {median:8.1f} {mean:8.1f} "
                f"{median - floor:9.1f} {mean - floor_mean:8.1f}"
            )
    handoff = statistics.median(samples[("thread hand-off", "bare wake-up and back")]) * 1e6
    anyio_call = statistics.median(samples[("no-op coroutine", "anyio portal.call")]) * 1e6
    ours = statistics.median(samples[("no-op coroutine", "j5aio.sync call")]) * 1e6
    futexes = statistics.median(samples[("thread hand-off", "a lock each way")]) * 1e6
    print(f"{'thread hand-off':<28} {'asyncio wake-up and back (floor)':<34} {handoff:8.1f}")
    print(f"{'thread hand-off':<28} {'a lock each way (floor)':<34} {futexes:8.1f}")
    direct = samples[(SIMULATED, "direct await")]
    facade = samples[(SIMULATED, "j5aio.sync facade")]
    median_overhead = (statistics.median(facade) - statistics.median(direct)) * 1e6
    mean_overhead = (statistics.fmean(facade) - statistics.fmean(direct)) * 1e6
    verdict = "meets" if max(median_overhead, mean_overhead) <= GOAL_US else "MISSES"
    print(
        f"\n{SIMULATED}: facade overhead {median_overhead:.1f} us median, "
        f"{mean_overhead:.1f} us mean ({verdict} the {GOAL_US:.0f} us goal)"
    )
    driven = samples[(SIMULATED, "caller drives the loop (no hand-off)")]
    print(
        f"{SIMULATED}: facade above the caller-driven floor "
        f"{(statistics.median(facade) - statistics.median(driven)) * 1e6:.1f} us median, "
        f"{(statistics.fmean(facade) - statistics.fmean(driven)) * 1e6:.1f} us mean"
    )
    print(f"j5aio.sync (no-op) against the asyncio hand-off floor: {ours - handoff:.1f} us")
    print(f"j5aio.sync (no-op) against the lock-each-way floor: {ours - futexes:.1f} us")
    print(f"j5aio.sync / anyio portal.call: {ours / anyio_call:.2f}")

    measure_after_pause(100)
    measure_idle()
    measure_ctrl_c(options.interrupts)
    shutdown()


if __name__ == "__main__":
    main()

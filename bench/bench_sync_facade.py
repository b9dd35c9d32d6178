"""How much a sync facade call costs on top of awaiting the same coroutine.

Measures, in one run, the median time of:

* a direct ``await`` inside an event loop (the floor);
* the facade: a blocking call through j5aio's portal thread (``j5aio.sync``);
* anyio's stock blocking portal (``portal.call``), for reference;
* the machine's floor for any thread portal: waking an event loop in another thread
  (``call_soon_threadsafe``) and being woken back by a lock, with no coroutine at all;

for a no-op coroutine and for a console backend call (``motor.get_power()`` on the SR v4
motor board's console backend, which answers from memory without printing). The rounds of
the three ways are interleaved so that machine noise hits them alike. Run::

    python bench/bench_sync_facade.py [--calls 20000] [--rounds 5]

Goal: at most 60 µs median overhead per facade call. The hand-off floor moves a lot with
the load on the host of this virtual machine, so read the facade's figure against the
floor and against anyio measured in the same run.
"""

from __future__ import annotations

import argparse
import asyncio
import statistics
import threading
import time
from collections.abc import Awaitable, Callable
from typing import Any

from anyio.from_thread import start_blocking_portal

from j5aio.backends.console.sr.v4 import SRV4MotorBoardConsoleBackend
from j5aio.boards.sr.v4 import MotorBoard
from j5aio.sync import MotorBoard as SyncMotorBoard
from j5aio.sync import shutdown
from j5aio.sync._runtime import call
from j5aio.sync.wrapping import wrap

GOAL_US = 60.0


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


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--calls", type=int, default=20000, help="calls per round")
    parser.add_argument("--rounds", type=int, default=5, help="interleaved rounds")
    options = parser.parse_args()

    core_board = MotorBoard("BENCH", SRV4MotorBoardConsoleBackend("BENCH"))
    motor = core_board.motors[0]
    sync_board = wrap(core_board)
    assert isinstance(sync_board, SyncMotorBoard)
    sync_motor = sync_board.motors[0]

    samples: dict[tuple[str, str], list[float]] = {}

    def add(case: str, way: str, values: list[float]) -> None:
        samples.setdefault((case, way), []).extend(values)

    handoff_loop = asyncio.new_event_loop()
    handoff_thread = threading.Thread(target=handoff_loop.run_forever, daemon=True)
    handoff_thread.start()
    with start_blocking_portal() as portal:
        for _ in range(options.rounds):
            n = options.calls
            add("thread hand-off", "bare wake-up and back", time_handoff(handoff_loop, n))
            add("no-op coroutine", "direct await", time_direct(noop, n))
            add("no-op coroutine", "j5aio.sync portal", time_blocking(lambda: call(noop), n))
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
    shutdown()
    handoff_loop.call_soon_threadsafe(handoff_loop.stop)
    handoff_thread.join()

    print(f"{options.rounds} rounds x {options.calls} calls; medians in microseconds\n")
    print(f"{'case':<28} {'way':<34} {'median':>8} {'overhead':>9}")
    worst = 0.0
    for case in ("no-op coroutine", "console motor.get_power()"):
        floor = statistics.median(samples[(case, "direct await")]) * 1e6
        for (this_case, way), values in samples.items():
            if this_case != case:
                continue
            median = statistics.median(values) * 1e6
            overhead = median - floor
            if way.startswith("j5aio"):
                worst = max(worst, overhead)
            print(f"{case:<28} {way:<34} {median:8.1f} {overhead:9.1f}")
    handoff = statistics.median(samples[("thread hand-off", "bare wake-up and back")]) * 1e6
    anyio_call = statistics.median(samples[("no-op coroutine", "anyio portal.call")]) * 1e6
    ours = statistics.median(samples[("no-op coroutine", "j5aio.sync portal")]) * 1e6
    print(f"{'thread hand-off':<28} {'bare wake-up and back (floor)':<34} {handoff:8.1f}")
    verdict = "meets" if worst <= GOAL_US else "MISSES"
    print(f"\nworst j5aio.sync overhead: {worst:.1f} us ({verdict} the {GOAL_US:.0f} us goal)")
    print(f"j5aio.sync above the bare hand-off floor: {ours - handoff:.1f} us")
    print(f"j5aio.sync / anyio portal.call: {ours / anyio_call:.2f}")


if __name__ == "__main__":
    main()

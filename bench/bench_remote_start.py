"""How soon a waiting robot starts after a start from outside (a remote start).

``trigger_start()`` is what the robot service's client calls on astoria's or sbot's
remote start, from its own thread. It wakes the waiting
:func:`~j5aio.competition.start.wait_for_start` at once; before, the wait looked for it
every ``POLL_INTERVAL`` (50 ms), so a start waited up to 50 ms, 25 ms on average.

Prints the median and 95th percentile, in milliseconds, of the time from the call (in
another thread) to the wait returning, for ``trigger_start`` and for the start file
(which is still looked for every ``POLL_INTERVAL``), interleaved round by round.

    PYTHONPATH=$PWD python bench/bench_remote_start.py [ROUNDS]
"""

from __future__ import annotations

import argparse
import os
import statistics
import tempfile
import threading
import time
from pathlib import Path

import anyio


async def one_start(kind: str, path: Path) -> float:
    """Seconds from the start (given in another thread) to the wait returning."""
    from j5aio.competition.start import trigger_start, wait_for_start

    began: list[float] = []

    def start_later() -> None:
        time.sleep(0.02)  # the wait is under way by then
        began.append(time.perf_counter())
        if kind == "trigger":
            trigger_start("remote start")
        else:
            path.touch()

    thread = threading.Thread(target=start_later)
    thread.start()
    await wait_for_start([], timeout=10)
    ended = time.perf_counter()
    thread.join()
    return ended - began[0]


async def main(rounds: int) -> None:
    folder = tempfile.mkdtemp(prefix="j5aio-bench-")
    path = Path(folder) / "start"
    os.environ["J5AIO_START_FILE"] = str(path)
    kinds = ("trigger", "start file")
    results: dict[str, list[float]] = {kind: [] for kind in kinds}
    for _ in range(rounds):
        for kind in kinds:
            results[kind].append(await one_start(kind, path))
    print(f"From the start to wait_for_start returning, {rounds} rounds (ms):")
    for kind, times in results.items():
        ms = sorted(t * 1000 for t in times)
        p95 = ms[min(len(ms) - 1, int(len(ms) * 0.95))]
        print(f"  {kind:>10}: median {statistics.median(ms):6.2f}  p95 {p95:6.2f}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("rounds", nargs="?", type=int, default=40, help="starts of each kind")
    anyio.run(main, parser.parse_args().rounds)

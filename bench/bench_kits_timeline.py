"""Where one iteration of bench_kits.py's async loop (four boards at once) spends its time.

The same four wire-timed simulators on ptys as ``bench/bench_kits.py``, the same loop
(``J5aioLoop.iteration``: ``at_once`` making the power, motor, servo and Arduino
requests). Each board's stream is wrapped to note when its request is written and when
its reply arrives; printed are the medians, in microseconds from the iteration's start,
of each write and each reply, and of the iteration's end. What lies on the critical path
is j5aio's (from the start to the slowest board's write, and from its reply to the end)
or the wire's and the simulator's (from that write to that reply; its wire time is
printed beside it). The wrapping adds a little to every figure.

Run: ``python bench/bench_kits_timeline.py [--iterations N]``.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path
from typing import Any

import anyio

sys.path.insert(0, str(Path(__file__).resolve().parent))

import bench_kits  # type: ignore[import-not-found]  # (the loop and the served kit)

ROLES = ("power", "motor", "servo", "arduino")


def note_times(stream: Any, role: str, marks: dict[str, float]) -> None:
    """Wrap ``stream`` so that its first write and last receive are noted in ``marks``."""
    send, send_nowait = stream.send, stream.send_nowait
    receive, receive_by = stream.receive, stream.receive_by

    async def timed_send(data: bytes) -> None:
        marks.setdefault(f"{role} written", time.perf_counter())
        await send(data)

    def timed_send_nowait(data: bytes) -> bool:
        marks.setdefault(f"{role} written", time.perf_counter())
        sent: bool = send_nowait(data)
        return sent

    async def timed_receive(max_bytes: int = 4096) -> bytes:
        chunk: bytes = await receive(max_bytes)
        marks[f"{role} reply"] = time.perf_counter()
        return chunk

    async def timed_receive_by(deadline: float, max_bytes: int = 4096) -> bytes | None:
        chunk: bytes | None = await receive_by(deadline, max_bytes)
        marks[f"{role} reply"] = time.perf_counter()
        return chunk

    stream.send, stream.send_nowait = timed_send, timed_send_nowait
    stream.receive, stream.receive_by = timed_receive, timed_receive_by


async def run(iterations: int) -> dict[str, list[float]]:
    """Time ``iterations`` iterations; return each mark's offsets from the start, in us."""
    offsets: dict[str, list[float]] = {}
    with bench_kits.served_kit("TIMELINE") as paths:
        loop = await bench_kits.J5aioLoop.attach(paths)
        marks: dict[str, float] = {}
        for role in ROLES:
            note_times(getattr(loop, role).backend.link.stream, role, marks)
        await loop.batch(20)  # warm up
        for index in range(iterations):
            marks.clear()
            start = time.perf_counter()
            await loop.iteration(index)
            marks["end"] = time.perf_counter()
            for name, moment in marks.items():
                offsets.setdefault(name, []).append((moment - start) * 1e6)
        await loop.close()
    return offsets


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--iterations", type=int, default=300, help="iterations timed")
    args = parser.parse_args(argv)
    offsets = anyio.run(run, args.iterations)
    median = {name: statistics.median(values) for name, values in offsets.items()}
    print(f"one iteration of the async loop, medians of {args.iterations} (us from its start)")
    for name in sorted(median, key=median.__getitem__):
        print(f"  {name:18} {median[name]:8.1f}")
    slowest = max(ROLES, key=lambda role: median[f"{role} reply"])
    written, reply = median[f"{slowest} written"], median[f"{slowest} reply"]
    wire = bench_kits.wire_ms(slowest) * 1e3
    print(
        f"critical path: the {slowest} board. j5aio before its write {written:.0f} us, "
        f"after its reply {median['end'] - reply:.0f} us; write to reply {reply - written:.0f}"
        f" us, of which the wire {wire:.0f} us and the simulator's process the rest"
    )


if __name__ == "__main__":
    main()

"""What many watching pages of the live view cost the robot's control loop.

A robot on the simulated kit runs a control loop (set a motor's power, read it back,
sleep 10 ms) while N pages watch its live view (WebSocket clients in a thread of their
own, as browsers elsewhere would be). Printed per N: the loop's iteration time beyond
its sleep (median, 99th percentile), and how many times a second the view read the
program in the robot's event loop (the snapshots: boards, arena, pose). Every page
shares one reading per tick, so the readings, and the loop's cost, should not grow
with N. Goal: the view delays a board call by <= 1 ms (p99 with 200 pages within 1 ms
of no page).

Run: ``PYTHONPATH=$PWD python bench/bench_view_pages.py [--pages 0,1,50,200] [--seconds 5]``
(needs ``pip install 'j5aio[view]'``).
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import io
import statistics
import threading
import time
from typing import Any

import anyio

LOOP_SLEEP = 0.01


def _watch(url: str, pages: int, stop: threading.Event, connected: list[int]) -> None:
    import aiohttp

    async def one(session: aiohttp.ClientSession) -> None:
        async with session.ws_connect(url.replace("/?", "/ws?")) as ws:
            connected[0] += 1
            while not stop.is_set():
                with contextlib.suppress(TimeoutError):
                    await ws.receive(timeout=0.2)

    async def watch() -> None:
        connector = aiohttp.TCPConnector(limit=0)
        async with aiohttp.ClientSession(connector=connector) as session:
            await asyncio.gather(*(one(session) for _ in range(pages)))

    asyncio.run(watch())


async def control_loop(pages: int, seconds: float) -> tuple[list[float], float]:
    """Return the loop's iteration times beyond its sleep, and the view's readings a second."""
    from j5aio.kit import KitRobot
    from j5aio.simulator.environment import SIMULATED_ENVIRONMENT
    from j5aio.simulator.kit import KitConfig, use_kit
    from j5aio.view import serve_view

    use_kit(KitConfig(motor_boards=1))
    readings = [0]
    async with contextlib.AsyncExitStack() as stack:
        robot = await stack.enter_async_context(KitRobot(environment=SIMULATED_ENVIRONMENT))
        live = await stack.enter_async_context(serve_view(out=io.StringIO()))
        server: Any = live.server
        snapshot = server._snapshot

        def counting(with_boards: bool) -> dict[str, Any]:
            readings[0] += 1
            taken: dict[str, Any] = snapshot(with_boards)
            return taken

        server._snapshot = counting
        stop = threading.Event()
        connected = [0]
        if pages:
            watcher = threading.Thread(
                target=_watch, args=(live.url, pages, stop, connected), daemon=True
            )
            watcher.start()
            stack.callback(watcher.join, 10)
            stack.callback(stop.set)
            with anyio.fail_after(60):
                while connected[0] < pages:  # noqa: ASYNC110 - counted in another thread
                    await anyio.sleep(0.05)
        motor = robot.motor_boards[0].motors[0]
        await anyio.sleep(0.5)  # settle
        readings[0] = 0
        times: list[float] = []
        began = time.perf_counter()
        i = 0
        while time.perf_counter() - began < seconds:
            started = time.perf_counter()
            await motor.set_power((i % 200) / 100 - 1)
            await motor.get_power()
            await anyio.sleep(LOOP_SLEEP)
            times.append(time.perf_counter() - started - LOOP_SLEEP)
            i += 1
        elapsed = time.perf_counter() - began
    return times, readings[0] / elapsed


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pages", default="0,1,50,200")
    parser.add_argument("--seconds", type=float, default=5.0)
    arguments = parser.parse_args()
    print(f"Control loop (set_power, get_power, sleep {LOOP_SLEEP * 1000:.0f} ms) "
          f"for {arguments.seconds:g} s while N pages watch the live view")
    print(f"  {'pages':>6}{'iterations':>12}{'median ms':>11}{'p99 ms':>9}{'readings/s':>12}")
    for pages in (int(p) for p in arguments.pages.split(",")):
        times, rate = anyio.run(control_loop, pages, arguments.seconds)
        ordered = sorted(times)
        p99 = ordered[int(0.99 * (len(ordered) - 1))]
        print(f"  {pages:>6}{len(times):>12}{statistics.median(times) * 1e3:>11.2f}"
              f"{p99 * 1e3:>9.2f}{rate:>12.1f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

"""Cost of the live view, measured side by side in one run (medians).

(a) CPU of the demo robot (``python -m j5aio demo``) without the view, with the view on and
    nobody connected, and with one browser (headless chromium) watching. The robot
    process's CPU time is read from /proc between two instants while its tasks run, so
    start-up is left out. Goals: view on and nobody watching <= +0.2 % of a core; one
    browser watching <= 5 % of a core (the robot process only, not the browser).
(b) Board-call delay: the time of one ``motor.set_power`` on the simulated kit, in
    process, without the view and with the view on and one page (a WebSocket client in a
    thread of the same process, the worst case for the GIL) watching. Goal: the view
    delays a call by <= 1 ms (median, 99th percentile and maximum are printed).

(c) Page latency: how long after ``motor.set_power`` returns a headless chromium watching
    the page shows the new value (its ``data-value``), polled every 2 ms through
    selenium (the polling's own time is included). Goal: within 200 ms. The browser
    tests check only that values arrive: a timed assertion fails on a loaded machine.

The rows of (a) are interleaved (off, idle, browser, off, ...) so that the load of a
shared machine falls on all of them alike.

Run: ``python bench/bench_view.py [--seconds S] [--repeats R] [--calls N]``
(needs ``pip install 'j5aio[view-test]'``; without chromium the browser row is skipped).
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import importlib.util
import io
import json
import os
import re
import shutil
import signal
import statistics
import subprocess
import sys
import threading
import time
from pathlib import Path
from typing import Any

import anyio

ROOT = Path(__file__).resolve().parent.parent
TICKS = os.sysconf("SC_CLK_TCK")


def _load_tool() -> Any:
    spec = importlib.util.spec_from_file_location(
        "view_screenshot_tool", ROOT / "tools" / "view_screenshot.py"
    )
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _cpu_seconds(pid: int) -> float:
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / TICKS  # utime + stime


def demo_cpu(mode: str, seconds: float, tool: Any) -> float:
    """Percent of a core the demo robot uses over ``seconds`` while its tasks run."""
    # Long enough to outlast a slow browser start; interrupted once measured.
    arguments = [sys.executable, "-m", "j5aio", "demo", "--seconds", str(seconds + 60)]
    if mode != "off":
        arguments.append("--view")
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    process = subprocess.Popen(
        arguments, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True, env=env
    )
    assert process.stdout is not None
    url = None
    for line in process.stdout:
        found = re.match(r"View: (\S+)", line)
        url = found.group(1) if found else url
        if "starting the tasks" in line:
            break
    driver = profile = None
    try:
        if mode == "browser":
            driver, profile = tool.launch_chromium()
            driver.get(url)
        time.sleep(1.0)
        if mode == "browser":
            assert driver is not None
            live = driver.execute_script("return document.getElementById('status').dataset.status")
            assert live == "live", live
        start = _cpu_seconds(process.pid)
        began = time.monotonic()
        time.sleep(seconds)
        used = _cpu_seconds(process.pid) - start
        elapsed = time.monotonic() - began
    finally:
        if driver is not None:
            driver.quit()
        if profile is not None:
            shutil.rmtree(profile, ignore_errors=True)
        process.send_signal(signal.SIGINT)
        process.communicate(timeout=20)
    return 100 * used / elapsed


async def call_times(calls: int, view: bool) -> list[float]:
    """Seconds per ``set_power`` call on the simulated kit, with or without a watched view."""
    from j5aio.kit import KitRobot
    from j5aio.simulator.environment import SIMULATED_ENVIRONMENT
    from j5aio.simulator.kit import KitConfig, use_kit
    from j5aio.view import serve_view

    use_kit(KitConfig(motor_boards=1))
    times: list[float] = []
    async with contextlib.AsyncExitStack() as stack:
        robot = await stack.enter_async_context(KitRobot(environment=SIMULATED_ENVIRONMENT))
        stop = threading.Event()
        if view:
            live = await stack.enter_async_context(serve_view(out=io.StringIO()))
            watcher = threading.Thread(target=_watch, args=(live.url, stop), daemon=True)
            watcher.start()
            stack.callback(watcher.join)
            stack.callback(stop.set)
            for _ in range(500):  # until the page is connected
                if live.watchers:
                    break
                await anyio.sleep(0.01)
        motor = robot.motor_boards[0].motors[0]
        for i in range(calls):
            started = time.perf_counter()
            await motor.set_power((i % 200) / 100 - 1)
            times.append(time.perf_counter() - started)
            if i % 50 == 0:
                await anyio.sleep(0.005)  # let time pass, as a robot program does
    return times


async def page_latencies(samples: int, tool: Any) -> list[float]:
    """Seconds from a ``set_power`` to headless chromium showing it, ``samples`` times."""
    from j5aio.kit import KitRobot
    from j5aio.simulator.environment import SIMULATED_ENVIRONMENT
    from j5aio.simulator.kit import KitConfig, use_kit
    from j5aio.view import serve_view

    use_kit(KitConfig(motor_boards=1))
    driver, profile = await anyio.to_thread.run_sync(tool.launch_chromium)
    selector = '[data-component="SIMMB0:motor:0"]'
    script = "const e = document.querySelector(arguments[0]); return e && Number(e.dataset.value);"

    def shown_within(value: float, started: float, limit: float = 10.0) -> float:
        while driver.execute_script(script, selector) != value:
            if time.perf_counter() - started > limit:
                raise RuntimeError(f"the page did not show {value} within {limit} s")
            time.sleep(0.002)
        return time.perf_counter() - started

    latencies: list[float] = []
    try:
        async with (
            KitRobot(environment=SIMULATED_ENVIRONMENT) as robot,
            serve_view(out=io.StringIO()) as live,
        ):
            motor = robot.motor_boards[0].motors[0]
            await motor.set_power(0.0)
            await anyio.to_thread.run_sync(driver.get, live.url)
            await anyio.to_thread.run_sync(shown_within, 0.0, time.perf_counter())
            for i in range(samples):
                power = round(0.01 * (i % 99 + 1), 2)
                await motor.set_power(power)
                started = time.perf_counter()
                latencies.append(await anyio.to_thread.run_sync(shown_within, power, started))
                await anyio.sleep(0.05 + 0.013 * (i % 4))  # land anywhere in a push tick
    finally:
        driver.quit()
        shutil.rmtree(profile, ignore_errors=True)
    return latencies


def _watch(url: str, stop: threading.Event) -> None:
    import aiohttp

    async def watch() -> None:
        async with (
            aiohttp.ClientSession() as session,
            session.ws_connect(url.replace("/?", "/ws?")) as ws,
        ):
            while not stop.is_set():
                with contextlib.suppress(TimeoutError):
                    message = await ws.receive(timeout=0.2)
                    json.loads(message.data)

    asyncio.run(watch())


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=8.0, help="CPU window per run")
    parser.add_argument("--repeats", type=int, default=3, help="runs of each kind")
    parser.add_argument("--calls", type=int, default=3000, help="board calls per delay run")
    parser.add_argument("--pages", type=int, default=60, help="page-latency samples")
    args = parser.parse_args()
    tool = _load_tool()
    reason = tool.missing_browser()
    modes = ["off", "idle"] + ([] if reason else ["browser"])
    if reason:
        print(f"(no browser row: {reason})")

    print(
        f"(a) CPU of the demo robot, % of one core, over {args.seconds:g} s, "
        f"median of {args.repeats} interleaved runs"
    )
    results: dict[str, list[float]] = {mode: [] for mode in modes}
    for _ in range(args.repeats):
        for mode in modes:
            results[mode].append(demo_cpu(mode, args.seconds, tool))
    base = statistics.median(results["off"])
    labels = {
        "off": "view off",
        "idle": "view on, nobody watching",
        "browser": "view on, one browser watching",
    }
    for mode in modes:
        median = statistics.median(results[mode])
        runs = ", ".join(f"{r:.2f}" for r in results[mode])
        extra = "" if mode == "off" else f"  ({median - base:+.2f} points vs off)"
        print(f"    {labels[mode]:<32}{median:6.2f} %{extra}   runs: {runs}")

    print(f"(b) one motor.set_power on the simulated kit, {args.calls} calls, in process")
    off = anyio.run(call_times, args.calls, False)
    on = anyio.run(call_times, args.calls, True)
    for name, times in (("view off", off), ("view on, one page watching", on)):
        ordered = sorted(times)
        p99 = ordered[int(0.99 * (len(ordered) - 1))]
        print(
            f"    {name:<32}median {statistics.median(times) * 1e6:7.1f} us   "
            f"p99 {p99 * 1e6:7.1f} us   max {max(times) * 1e6:8.1f} us"
        )
    delay = statistics.median(on) - statistics.median(off)
    p99_delay = sorted(on)[int(0.99 * (len(on) - 1))] - sorted(off)[int(0.99 * (len(off) - 1))]
    print(
        f"    delay added by the view: median {delay * 1e6:+.1f} us, p99 {p99_delay * 1e6:+.1f} us"
    )

    if reason:
        return 0
    latencies = sorted(anyio.run(page_latencies, args.pages, tool))
    p95 = latencies[int(0.95 * (len(latencies) - 1))]
    print(
        f"(c) set_power to the page showing it, headless chromium, {args.pages} samples: "
        f"median {statistics.median(latencies) * 1e3:.0f} ms, p95 {p95 * 1e3:.0f} ms, "
        f"max {latencies[-1] * 1e3:.0f} ms (goal: 200 ms)"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())

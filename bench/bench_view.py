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
    arguments = [sys.executable, "-m", "j5aio", "demo", "--seconds", str(seconds + 4)]
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
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""How soon a waiting robot starts after a start from outside (a remote start).

``trigger_start()`` is what the robot service's client calls on astoria's or sbot's
remote start, from its own thread. It wakes the waiting
:func:`~j5aio.competition.start.wait_for_start` at once; before, the wait looked for it
every ``POLL_INTERVAL`` (50 ms), so a start waited up to 50 ms, 25 ms on average.

Prints the median and 95th percentile, in milliseconds, of the time from the call (in
another thread) to the wait returning, for ``trigger_start`` and for the start file
(which is still looked for every ``POLL_INTERVAL``), interleaved round by round.

Over the broker (with ``j5aio[robot]`` and Debian's mosquitto): a mosquitto of the
bench's own, the robot service's client (:class:`~j5aio.service.RobotService`) on the
waiting loop, and a peer client in another thread with its own event loop publishing
astoria's ``broadcast/start_button`` event (and sbot's ``start_button``); the time is from
the peer's publish call to ``wait_for_start`` returning. Goal: p95 <= 20 ms.

It also prints what :func:`~j5aio.service.service.publish_frame` costs its caller (a
camera's thread) while the service runs.

Broker recovery (``--restarts``): the broker is killed mid-run and started again; printed
are the times from its return (the moment it accepts connections) to the client being
connected again and to a remote start working again. Goal: both within 2 s.

    PYTHONPATH=$PWD python bench/bench_remote_start.py [ROUNDS] [--broker-rounds N]
        [--restarts N]
"""

from __future__ import annotations

import argparse
import contextlib
import json
import logging
import os
import statistics
import tempfile
import threading
import time
from pathlib import Path
from typing import Any

import anyio
import anyio.to_thread


async def one_start(kind: str, path: Path) -> float:
    """Seconds from the start (given in another thread) to the wait returning."""
    from j5aio.competition.start import is_waiting, trigger_start, wait_for_start

    began: list[float] = []

    def start_later() -> None:
        # Only once the wait is under way (it has cleared any old start file by then: a
        # file there before the wait begins is an old one; a fixed pause lost that race
        # under load).
        deadline = time.monotonic() + 10
        while not is_waiting() and time.monotonic() < deadline:
            time.sleep(0.001)
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


class PeerThread:
    """A publishing client in a thread of its own, with its own event loop."""

    def __init__(self, port: int) -> None:
        import asyncio

        self._loop = asyncio.new_event_loop()
        self._thread = threading.Thread(target=self._loop.run_forever, daemon=True)
        self._thread.start()
        self._port = port
        self._client: Any = None

    def _run(self, coroutine: Any) -> Any:
        import asyncio

        return asyncio.run_coroutine_threadsafe(coroutine, self._loop).result(timeout=30)

    def connect(self) -> None:
        import aiomqtt

        async def connect() -> Any:
            client = aiomqtt.Client("127.0.0.1", self._port)
            await client.__aenter__()
            return client

        self._client = self._run(connect())

    def publish_at(self, topic: str, payload: str, began: list[float]) -> None:
        """Publish (QoS 1, as astoria), noting the moment of the call."""

        async def publish() -> None:
            began.append(time.perf_counter())
            await self._client.publish(topic, payload, qos=1)

        self._run(publish())

    def close(self) -> None:
        async def close() -> None:
            if self._client is not None:
                with contextlib.suppress(Exception):
                    await self._client.__aexit__(None, None, None)

        self._run(close())
        self._loop.call_soon_threadsafe(self._loop.stop)
        self._thread.join()
        self._loop.close()


ASTORIA_START = json.dumps(
    {"event_name": "start_button", "sender_name": "bench", "priority": 0}
)
SBOT_START = json.dumps({"pressed": True})


async def broker_start(peer: PeerThread, topic: str, payload: str) -> float:
    """Seconds from the peer's publish to the wait returning."""
    from j5aio.competition.start import wait_for_start

    began: list[float] = []

    def start_later() -> None:
        time.sleep(0.02)  # the wait is under way by then
        peer.publish_at(topic, payload, began)

    thread = threading.Thread(target=start_later)
    thread.start()
    how = await wait_for_start([], timeout=10)
    ended = time.perf_counter()
    thread.join()
    assert how == "remote start", how
    return ended - began[0]


def summary(name: str, seconds: list[float]) -> str:
    ms = sorted(t * 1000 for t in seconds)
    p95 = ms[min(len(ms) - 1, int(len(ms) * 0.95))]
    return f"  {name:>22}: median {statistics.median(ms):7.2f}  p95 {p95:7.2f}  max {ms[-1]:7.2f}"


async def over_the_broker(rounds: int, restarts: int) -> None:
    try:
        import aiomqtt  # noqa: F401 - only to say what is missing

        from j5aio.testing.mosquitto import start_broker

        broker, folder = start_broker()
    except (ImportError, RuntimeError) as exc:
        print(f"Over the broker: skipped ({exc}; needs j5aio[robot] and mosquitto)")
        return
    from j5aio.competition.start import clear_trigger
    from j5aio.service import RobotService, ServiceConfig

    config = ServiceConfig(host="127.0.0.1", port=broker.port, topic_prefix="astoria")
    try:
        async with RobotService(config) as service:
            await service.wait_connected(timeout=10)
            clear_trigger()
            if rounds:
                await starts_over_the_broker(broker.port, rounds)
                await frame_offer_cost(service)
            if restarts:
                await broker_restarts(broker, service, restarts)
    finally:
        broker.stop()
        folder.cleanup()


async def starts_over_the_broker(port: int, rounds: int) -> None:
    peer = PeerThread(port)
    try:
        peer.connect()
        # A start comes long after the robot connected. Within the first 40 ms or so
        # the broker's first message to it can wait for TCP's delayed acknowledgement
        # of what it sent on connecting (mosquitto leaves Nagle's algorithm on), which
        # is not what a match sees.
        await anyio.sleep(0.2)
        results: dict[str, list[float]] = {"astoria start_button": [], "sbot start_button": []}
        for _ in range(rounds):
            results["astoria start_button"].append(
                await broker_start(peer, "astoria/broadcast/start_button", ASTORIA_START)
            )
            results["sbot start_button"].append(
                await broker_start(peer, "astoria/start_button", SBOT_START)
            )
    finally:
        peer.close()
    print(f"Over the broker, from the peer's publish to wait_for_start returning, "
          f"{rounds} rounds (ms):")
    for name, times in results.items():
        print(summary(name, times))


async def frame_offer_cost(service: Any, calls: int = 20_000) -> None:
    """What publish_frame costs its caller (the camera's thread) while the service runs."""
    from j5aio.service import publish_frame

    jpeg = b"\xff\xd8" + bytes(20_000) + b"\xff\xd9"
    costs: list[float] = []
    taken = 0
    for _ in range(calls):
        began = time.perf_counter()
        taken += publish_frame(jpeg)
        costs.append(time.perf_counter() - began)
        if len(costs) % 1000 == 0:
            await anyio.sleep(0.01)  # let the service send what it took
    costs.sort()
    print(f"publish_frame's cost to its caller, {calls} calls ({taken} frames taken): "
          f"median {costs[len(costs) // 2] * 1e6:.2f} us, "
          f"p99 {costs[int(len(costs) * 0.99)] * 1e6:.2f} us")


async def broker_restarts(broker: Any, service: Any, restarts: int) -> None:
    reconnected: list[float] = []
    working: list[float] = []
    for _ in range(restarts):
        broker.stop()
        with anyio.fail_after(10):
            while service.connected:  # noqa: ASYNC110 - the client notices on its own
                await anyio.sleep(0.001)
        await anyio.sleep(0.5)  # the broker stays away a while
        # started from a worker thread: the client's retries go on meanwhile, as they
        # would while a real broker restarts
        back = await anyio.to_thread.run_sync(broker.start)
        await service.wait_connected(timeout=10)
        reconnected.append(time.perf_counter() - back)
        peer = PeerThread(broker.port)
        try:
            peer.connect()
            await broker_start(peer, "astoria/broadcast/start_button", ASTORIA_START)
        finally:
            peer.close()
        working.append(time.perf_counter() - back)
    print(f"Broker killed and restarted, {restarts} times, from its return (ms):")
    print(summary("client connected again", reconnected))
    print(summary("remote start works", working))


async def main(rounds: int, broker_rounds: int, restarts: int) -> None:
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
        print(summary(kind, times))
    if broker_rounds or restarts:
        await over_the_broker(broker_rounds, restarts)


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("rounds", nargs="?", type=int, default=40, help="starts of each kind")
    parser.add_argument("--broker-rounds", type=int, default=100,
                        help="remote starts over the broker, of each kind (0: none)")
    parser.add_argument("--restarts", type=int, default=5,
                        help="times the broker is killed and restarted (0: none)")
    args = parser.parse_args()
    # the service says so when the broker goes and comes back; the figures are the point
    logging.getLogger("j5aio.service").setLevel(logging.ERROR)
    anyio.run(main, args.rounds, args.broker_rounds, args.restarts)

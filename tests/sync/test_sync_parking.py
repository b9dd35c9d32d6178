"""The portal loop's selector: it sleeps on a lock while it watches no file, and wakes."""

from __future__ import annotations

import asyncio
import functools
import socket
import threading
import time
from collections.abc import Callable, Iterator

import anyio
import anyio.to_thread
import pytest

from j5aio.sync import _selectors
from j5aio.sync._runtime import call, get_loop

pytestmark = pytest.mark.skipif(not _selectors.CAN_PARK, reason="a selector event loop only")

LIVENESS = 10.0  # generous: only a hang fails


def in_thread(fn: Callable[[], object]) -> tuple[threading.Thread, list[object]]:
    """Run ``fn`` in a new thread; its result (or exception) lands in the list."""
    out: list[object] = []

    def run() -> None:
        try:
            out.append(fn())
        except BaseException as exc:  # handed to the test
            out.append(exc)

    thread = threading.Thread(target=run, daemon=True)
    thread.start()
    return thread, out


@pytest.fixture
def selector() -> Iterator[_selectors.ParkingSelector]:
    chosen = _selectors.ParkingSelector()
    yield chosen
    chosen.close()


def test_a_ring_before_the_wait_makes_it_return_at_once(
    selector: _selectors.ParkingSelector,
) -> None:
    selector.ring()
    thread, out = in_thread(lambda: selector.select(None))
    thread.join(LIVENESS)
    assert out == [[]]


def test_a_ring_wakes_a_parked_loop(selector: _selectors.ParkingSelector) -> None:
    waiting = threading.Event()
    selector.before_wait = waiting.set
    thread, out = in_thread(lambda: selector.select(None))
    assert waiting.wait(LIVENESS)
    deadline = time.monotonic() + LIVENESS
    while selector._mode != selector._PARKED:  # parked on the bell now
        assert time.monotonic() < deadline
        time.sleep(0.001)
    selector.ring()
    thread.join(LIVENESS)
    assert out == [[]]
    assert selector._mode == selector._AWAKE and not selector._rung


def test_a_wait_times_out_and_a_late_ring_only_shortens_the_next(
    selector: _selectors.ParkingSelector,
) -> None:
    assert selector.select(0.01) == []
    selector.ring()  # nobody parked: remembered
    assert selector.select(None) == []  # returns at once
    assert selector.select(0.01) == []  # and only once: this one times out again
    assert selector._bell.locked()


def test_hooks_run_around_every_wait(selector: _selectors.ParkingSelector) -> None:
    seen: list[str] = []
    selector.before_wait = lambda: seen.append("before")
    selector.after_wait = lambda: seen.append("after")
    selector.select(0)
    selector.select(0.001)
    assert seen == ["before", "after", "before", "after"]


def test_with_files_watched_a_ring_goes_through_the_pipe(
    selector: _selectors.ParkingSelector,
) -> None:
    watched, peer = socket.socketpair()
    pipe_in, pipe_out = socket.socketpair()
    try:
        selector.register(watched, 1)
        selector.register(pipe_in, 1)
        selector.own_files = 1

        def write_to_pipe() -> None:
            pipe_out.send(b"\0")

        selector.write_to_pipe = write_to_pipe
        assert selector.get_key(watched).fileobj is watched
        selector.modify(watched, 1, "data")
        waiting = threading.Event()
        selector.before_wait = waiting.set
        thread, out = in_thread(lambda: selector.select(None))
        assert waiting.wait(LIVENESS)
        deadline = time.monotonic() + LIVENESS
        while selector._mode != selector._IN_EPOLL:
            assert time.monotonic() < deadline
            time.sleep(0.001)
        selector.ring()
        thread.join(LIVENESS)
        assert [key.fileobj for key, _ in out[0]] == [pipe_in]  # type: ignore[attr-defined]
        peer.send(b"x")
        selector.ring()  # rung while awake: the next wait only polls
        assert {key.fileobj for key, _ in selector.select(None)} == {watched, pipe_in}
        selector.unregister(watched)
        selector.unregister(pipe_in)
    finally:
        for sock in (watched, peer, pipe_in, pipe_out):
            sock.close()


async def add(a: int, b: int) -> int:
    await anyio.lowlevel.checkpoint()
    return a + b


@pytest.mark.usefixtures("handoff_portal")
def test_the_portal_loop_parks_when_it_watches_no_file() -> None:
    loop = get_loop()
    assert isinstance(loop, _selectors.ParkingLoop)
    assert call(add, 1, 2) == 3
    assert len(loop.parking.get_map()) == loop.parking.own_files


@pytest.mark.usefixtures("handoff_portal")
def test_calls_are_served_while_the_portal_loop_watches_a_file() -> None:
    watched, peer = socket.socketpair()
    watched.setblocking(False)
    received: list[bytes] = []

    async def watch() -> None:
        asyncio.get_running_loop().add_reader(watched, lambda: received.append(watched.recv(9)))

    async def unwatch() -> None:
        asyncio.get_running_loop().remove_reader(watched)

    loop = get_loop()
    assert isinstance(loop, _selectors.ParkingLoop)
    call(watch)
    try:
        assert len(loop.parking.get_map()) > loop.parking.own_files
        assert [call(add, n, 1) for n in range(50)] == list(range(1, 51))
        peer.send(b"byte")
        deadline = time.monotonic() + LIVENESS
        while not received:
            assert time.monotonic() < deadline
            call(anyio.sleep, 0.01)
        assert received == [b"byte"]
    finally:
        call(unwatch)
        watched.close()
        peer.close()


@pytest.mark.usefixtures("either_portal")
def test_results_from_worker_threads_wake_the_parked_loop() -> None:
    # anyio hands a worker thread's result back with call_soon_threadsafe.
    thread, out = in_thread(
        lambda: [call(anyio.to_thread.run_sync, time.sleep, 0.001) for _ in range(20)]
    )
    thread.join(LIVENESS)
    assert out == [[None] * 20]


@pytest.mark.usefixtures("either_portal")
def test_many_threads_calling_at_once_all_get_their_own_results() -> None:
    def caller(base: int) -> list[int]:
        return [call(add, base, n) for n in range(200)]

    threads = [in_thread(functools.partial(caller, base)) for base in (0, 1000, 2000, 3000)]
    for thread, _ in threads:
        thread.join(LIVENESS)
    assert [out for _, out in threads] == [
        [[base + n for n in range(200)]] for base in (0, 1000, 2000, 3000)
    ]

"""Tests of PressWatch: one poll stream shared by every task waiting for a press."""

from __future__ import annotations

from collections.abc import Callable

import anyio
import anyio.lowlevel
import pytest

from j5aio.backends.press_watch import PressWatch
from j5aio.errors import CommunicationError


class FakeBoard:
    """A poll stream the test drives: it runs until the test presses or breaks the board."""

    def __init__(self) -> None:
        self.streams = 0  # streams started
        self.running = 0  # streams running now
        self.fresh: list[bool] = []
        self.reports: list[Callable[[], None]] = []
        self._changed = anyio.Event()
        self.error: Exception | None = None

    async def stream(self, report: Callable[[], None], *, fresh: bool) -> None:
        self.streams += 1
        self.running += 1
        self.fresh.append(fresh)
        self.reports.append(report)
        try:
            while True:
                changed = self._changed
                if self.error is not None:
                    raise self.error
                await changed.wait()
        finally:
            self.running -= 1

    def press(self) -> None:
        """Report a press through the newest stream's callback (as a board's read would)."""
        self.reports[-1]()

    def fail(self, error: Exception) -> None:
        self.error = error
        self._changed.set()
        self._changed = anyio.Event()


async def settle(condition: Callable[[], bool]) -> None:
    with anyio.fail_after(30):
        while not condition():
            await anyio.lowlevel.checkpoint()


class Waiters:
    """A leader that the test cancels, and waiters that count their returns."""

    def __init__(self, watch: PressWatch) -> None:
        self.watch = watch
        self.leader = anyio.CancelScope()
        self.done = 0

    async def lead(self) -> None:
        with self.leader:
            await self.watch.wait()

    async def wait(self) -> None:
        await self.watch.wait()
        self.done += 1


async def test_many_waiters_one_stream_and_it_stops_when_nobody_waits() -> None:
    board = FakeBoard()
    watch = PressWatch(board.stream)
    done = 0

    async def wait() -> None:
        nonlocal done
        await watch.wait()
        done += 1

    async with anyio.create_task_group() as group:
        for _ in range(5):
            group.start_soon(wait)
        await settle(lambda: watch.waiters == 5)
        assert board.streams == 1
        assert board.running == 1
        assert watch.polling
        board.press()
    assert done == 5
    assert board.running == 0
    assert not watch.polling
    assert watch.waiters == 0


async def test_a_cancelled_leader_hands_the_stream_on() -> None:
    board = FakeBoard()
    watch = PressWatch(board.stream)
    waiters = Waiters(watch)

    async with anyio.create_task_group() as group:
        group.start_soon(waiters.lead)
        await settle(lambda: watch.polling)
        leader = waiters.leader
        wait = waiters.wait
        group.start_soon(wait)
        group.start_soon(wait)
        await settle(lambda: watch.waiters == 3)
        leader.cancel()
        await settle(lambda: board.streams == 2 and watch.waiters == 2)
        assert board.running == 1  # one stream at a time, still
        assert board.fresh == [True, False]  # the waiters kept waiting: nothing to forget
        board.press()
    assert waiters.done == 2


async def test_a_press_reported_late_by_a_cancelled_stream_is_not_lost() -> None:
    board = FakeBoard()
    watch = PressWatch(board.stream)
    waiters = Waiters(watch)

    async with anyio.create_task_group() as group:
        group.start_soon(waiters.lead)
        await settle(lambda: watch.polling)
        leader = waiters.leader
        wait = waiters.wait
        group.start_soon(wait)
        await settle(lambda: watch.waiters == 2)
        leader.cancel()
        await settle(lambda: board.streams == 2)
        # The first stream's read saw the press as its leader was cancelled: its report
        # arrives now, while the second stream runs. The waiter returns, and the second
        # stream stops.
        board.reports[0]()
    assert waiters.done == 1
    assert board.running == 0


async def test_a_failing_stream_fails_every_waiter_then_a_new_wait_starts_afresh() -> None:
    board = FakeBoard()
    watch = PressWatch(board.stream)
    errors: list[BaseException] = []

    async def wait() -> None:
        with pytest.raises(CommunicationError) as info:
            await watch.wait()
        errors.append(info.value)

    async with anyio.create_task_group() as group:
        for _ in range(3):
            group.start_soon(wait)
        await settle(lambda: watch.waiters == 3)
        board.fail(CommunicationError("Power Board: no answer"))
    assert len(errors) == 3
    assert all(error is errors[0] for error in errors)
    assert board.running == 0
    board.error = None

    async def press_soon() -> None:
        await settle(lambda: board.running == 1)
        board.press()

    async with anyio.create_task_group() as group:
        group.start_soon(press_soon)
        await watch.wait()  # the old failure is not this wait's
    assert board.fresh == [True, True]


async def test_a_press_before_the_wait_does_not_count() -> None:
    board = FakeBoard()
    watch = PressWatch(board.stream)

    async with anyio.create_task_group() as group:
        group.start_soon(watch.wait)
        await settle(lambda: watch.polling)
        board.press()
    # A press the stream saw before this wait began is not this wait's.
    with anyio.move_on_after(0.01) as scope:
        await watch.wait()
    assert scope.cancelled_caught

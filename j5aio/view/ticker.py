"""One reading per tick, shared by every page that watches.

What the live view reads in the robot's event loop (the boards' states, the simulated
arena) costs that loop time. Read once per page, it would cost as much again for every
open page; a :class:`SharedTicker` reads once per tick, in one task, while anyone
listens, and each listener takes the latest reading. A listener that is slow skips
readings instead of queueing them.
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Awaitable, Callable
from typing import Generic, TypeVar

__all__ = ["SharedTicker"]

LOGGER = logging.getLogger(__name__)

ReadingT = TypeVar("ReadingT")


class SharedTicker(Generic[ReadingT]):
    """Calls ``take(tick)`` every ``period`` seconds while it has listeners.

    Used from one event loop (the view server's). ``tick`` counts from 0 each time the
    first listener arrives.

    :param take: makes one reading; its exceptions are logged and the reading skipped.
    :param period: seconds between the starts of two readings.
    """

    def __init__(self, take: Callable[[int], Awaitable[ReadingT]], period: float) -> None:
        if not period > 0:
            raise ValueError(f"the period must be a positive number of seconds, not {period!r}")
        self._take = take
        self._period = period
        self._listeners = 0
        self._task: asyncio.Task[None] | None = None
        self._latest: tuple[int, ReadingT] | None = None
        self._changed = asyncio.Event()
        #: How many readings were taken since the ticker was made.
        self.readings = 0

    @property
    def listeners(self) -> int:
        """How many listeners there are."""
        return self._listeners

    def add_listener(self) -> None:
        """One more listener; the first starts the readings."""
        self._listeners += 1
        if self._task is None:
            self._latest = None
            self._task = asyncio.get_running_loop().create_task(self._run())

    def remove_listener(self) -> None:
        """One listener fewer; when none is left, the readings stop."""
        self._listeners -= 1
        if self._listeners <= 0 and self._task is not None:
            self._listeners = 0
            self._task.cancel()
            self._task = None

    async def next_after(self, seen: int) -> tuple[int, ReadingT]:
        """Wait for a reading newer than tick ``seen`` (-1: any); return ``(tick, reading)``.

        A listener that took tick 3 and comes back after tick 7 gets tick 7: the readings
        in between are skipped.
        """
        while self._latest is None or self._latest[0] <= seen:
            self._changed.clear()
            await self._changed.wait()
        return self._latest

    async def _run(self) -> None:
        loop = asyncio.get_running_loop()
        tick = 0
        while True:
            started = loop.time()
            try:
                reading = await self._take(tick)
            except Exception:  # never let one reading stop the view
                LOGGER.exception("live view: a reading failed")
            else:
                self.readings += 1
                self._latest = (tick, reading)
                self._changed.set()
            tick += 1
            await asyncio.sleep(max(0.0, started + self._period - loop.time()))

"""The live view's shared ticker: one reading per tick, however many listen."""

from __future__ import annotations

import asyncio
import logging

import pytest

from j5aio.view.ticker import SharedTicker


async def test_listeners_share_readings_and_the_last_one_stops_them() -> None:
    taken: list[int] = []

    async def take(tick: int) -> int:
        taken.append(tick)
        return tick * 10

    ticker = SharedTicker(take, 0.001)
    ticker.add_listener()
    ticker.add_listener()
    assert ticker.listeners == 2
    first = await ticker.next_after(-1)
    again = await ticker.next_after(-1)  # another listener gets the same reading
    assert first == again == (0, 0)
    later = await ticker.next_after(first[0])
    assert later[0] > first[0] and later[1] == later[0] * 10
    ticker.remove_listener()
    ticker.remove_listener()
    assert ticker.listeners == 0
    await asyncio.sleep(0.01)
    count = len(taken)
    await asyncio.sleep(0.01)
    assert len(taken) == count  # no listener: no reading
    assert ticker.readings == count
    ticker.add_listener()  # a new first listener starts again from tick 0
    assert await ticker.next_after(-1) == (0, 0)
    ticker.remove_listener()


async def test_a_failed_reading_is_logged_and_skipped(caplog: pytest.LogCaptureFixture) -> None:
    async def take(tick: int) -> int:
        if tick == 0:
            raise RuntimeError("the program is busy")
        return tick

    ticker = SharedTicker(take, 0.001)
    ticker.add_listener()
    with caplog.at_level(logging.ERROR, "j5aio.view.ticker"):
        assert await ticker.next_after(-1) == (1, 1)
    assert "a reading failed" in caplog.text
    ticker.remove_listener()


def test_the_period_must_be_positive() -> None:
    async def take(tick: int) -> int:
        return tick

    with pytest.raises(ValueError, match="positive"):
        SharedTicker(take, 0)

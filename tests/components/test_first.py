"""Tests of first_of: the first of several waits, with tasks beside them."""

from __future__ import annotations

import anyio
import anyio.lowlevel
import pytest

from j5aio.components._first import first_of
from j5aio.errors import CommunicationError


async def test_the_first_wait_wins_and_the_rest_is_cancelled() -> None:
    fast = anyio.Event()
    cancelled: list[str] = []

    async def forever(name: str) -> str:
        try:
            await anyio.sleep_forever()
        finally:
            cancelled.append(name)
        raise AssertionError("unreachable")  # pragma: no cover

    async def soon() -> str:
        await fast.wait()
        return "soon"

    async def beside() -> None:
        fast.set()
        await forever("beside")

    result = await first_of([lambda: forever("slow"), soon], beside=[beside])
    assert result == "soon"
    assert sorted(cancelled) == ["beside", "slow"]


async def test_a_single_failure_is_raised_as_itself() -> None:
    async def broken() -> str:
        raise CommunicationError("Power Board: no answer")

    with pytest.raises(CommunicationError, match="no answer"):
        await first_of([anyio.sleep_forever, broken])


async def test_several_failures_stay_a_group() -> None:
    async def broken(n: int) -> str:
        await anyio.lowlevel.checkpoint()
        raise CommunicationError(f"board {n}")

    async def both_fail_at_once() -> str:
        return await first_of([lambda: broken(1)], beside=[lambda: broken(2)])

    with pytest.raises(ExceptionGroup) as info:
        await both_fail_at_once()
    assert len(info.value.exceptions) == 2


async def test_no_wait_is_refused() -> None:
    with pytest.raises(ValueError, match="at least one wait"):
        await first_of([])


async def test_a_failure_inside_a_nested_group_is_raised_as_itself() -> None:
    async def nested() -> str:
        async with anyio.create_task_group() as group:
            group.start_soon(anyio.lowlevel.checkpoint)
            raise CommunicationError("Power Board: no answer")
        return "unreachable"  # pragma: no cover

    with pytest.raises(CommunicationError, match="no answer"):
        await first_of([nested])

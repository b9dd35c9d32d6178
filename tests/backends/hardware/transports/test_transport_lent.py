"""A lent stream: closing the loan leaves the stream open, and wakes a waiting reader."""

from __future__ import annotations

import anyio
import pytest

from j5aio.backends.hardware.transports.lent import LentStream
from j5aio.backends.hardware.transports.memory import memory_stream_pair
from j5aio.errors import BoardDisconnectionError


async def test_a_loan_passes_bytes_both_ways_and_its_end_leaves_the_stream_open() -> None:
    ours, board = memory_stream_pair("port")
    lent = LentStream(ours)
    assert lent.name == ours.name and not lent.is_closed
    await lent.send(b"ping")
    assert await board.receive() == b"ping"
    await board.send(b"pong")
    assert await lent.receive() == b"pong"
    await lent.aclose()
    assert lent.is_closed and not ours.is_closed
    with pytest.raises(BoardDisconnectionError, match="no longer lent"):
        await lent.send(b"x")
    with pytest.raises(BoardDisconnectionError, match="no longer lent"):
        await lent.receive()
    await ours.send(b"still open")
    assert await board.receive() == b"still open"
    await ours.aclose()
    await board.aclose()


async def test_ending_the_loan_wakes_a_reader_and_keeps_later_bytes_for_the_owner() -> None:
    ours, board = memory_stream_pair("port")
    lent = LentStream(ours)
    woken: list[type[BaseException]] = []

    async def read() -> None:
        try:
            await lent.receive()
        except BoardDisconnectionError as error:
            woken.append(type(error))

    async with anyio.create_task_group() as group:
        group.start_soon(read)
        await anyio.wait_all_tasks_blocked()
        lent.close_now()
    assert woken == [BoardDisconnectionError]
    await board.send(b"next")
    assert await ours.receive() == b"next"
    await ours.aclose()
    await board.aclose()


async def test_a_closed_stream_ends_the_loan_too() -> None:
    ours, board = memory_stream_pair("port")
    lent = LentStream(ours)
    await ours.aclose()
    assert lent.is_closed
    with pytest.raises(BoardDisconnectionError):
        await lent.send(b"x")
    await board.aclose()

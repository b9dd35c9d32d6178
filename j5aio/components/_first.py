"""Wait for the first of several things, with others running beside the wait."""

from __future__ import annotations

from collections.abc import Awaitable, Callable, Sequence
from typing import TypeVar

import anyio

__all__ = ["first_of"]

T = TypeVar("T")


async def first_of(
    waits: Sequence[Callable[[], Awaitable[T]]],
    beside: Sequence[Callable[[], Awaitable[object]]] = (),
) -> T:
    """Run every wait and every ``beside`` task at once; return the first wait's result.

    Everything still running is then cancelled. A failure of any of them cancels the
    others and is raised as it is (not in an exception group) when it is the only one.

    :param waits: what may end the whole (at least one).
    :param beside: what runs only while waiting (flashing an LED, say).
    :raises ValueError: ``waits`` is empty.
    """
    if not waits:
        raise ValueError("first_of needs at least one wait")
    results: list[T] = []
    try:
        async with anyio.create_task_group() as group:

            async def run(wait: Callable[[], Awaitable[T]]) -> None:
                result = await wait()
                if not results:
                    results.append(result)
                group.cancel_scope.cancel()

            async def run_beside(task: Callable[[], Awaitable[object]]) -> None:
                await task()

            for wait in waits:
                group.start_soon(run, wait)
            for task in beside:
                group.start_soon(run_beside, task)
    except BaseExceptionGroup as errors:
        leaves = _leaves(errors)
        if len(leaves) == 1:
            raise leaves[0] from None
        raise
    return results[0]


def _leaves(group: BaseExceptionGroup[BaseException]) -> list[BaseException]:
    found: list[BaseException] = []
    for error in group.exceptions:
        if isinstance(error, BaseExceptionGroup):
            found += _leaves(error)
        else:
            found.append(error)
    return found

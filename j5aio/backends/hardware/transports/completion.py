"""Finish what was started on a board, whatever cancels the caller.

anyio shields keep anyio cancellation out of an exchange, but ``asyncio.Task.cancel()``
(which ``asyncio.timeout`` and ``asyncio.wait_for`` use) breaks through them. A team's
code will use those, so a link cannot rely on shields alone: an exchange torn half way
leaves its reply on the line, and a cache updated after the exchange would miss a
change the board did make.

:func:`run_to_completion` runs the critical part in a task of its own, which nothing but
the end of the event loop cancels, and waits for it. A caller cancelled meanwhile (by
anyio or natively) keeps waiting, and its cancellation is raised once the part has
finished: at worst one timeout later, as with an anyio shield. So within the part:

* the reply to a request is always read by the request that asked for it;
* a callback given the reply (``then=`` of the links) always runs when the board has
  answered, so caches follow what the board was told, even for a cancelled caller.
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Awaitable, Callable
from typing import TypeVar

import anyio

__all__ = ["run_to_completion"]

T = TypeVar("T")

_log = logging.getLogger(__name__)


async def run_to_completion(work: Callable[[], Awaitable[T]]) -> T:
    """Run ``work()`` to its end even if the caller is cancelled; return its result.

    A cancellation that arrives meanwhile (anyio or ``Task.cancel``) is raised after
    ``work`` has finished; ``work``'s own error, if any, is then only logged. ``work``
    must bound its own time (a timeout inside it).
    """

    async def run() -> T:
        return await work()

    task = asyncio.get_running_loop().create_task(run())
    cancelled: BaseException | None = None
    with anyio.CancelScope(shield=True):
        while not task.done():
            try:
                await asyncio.wait((task,))
            except asyncio.CancelledError as exc:  # Task.cancel: keep waiting, raise later
                cancelled = exc
    if cancelled is not None:
        if not task.cancelled() and task.exception() is not None:
            _log.debug("a cancelled caller's board call failed: %r", task.exception())
        raise cancelled
    return task.result()

"""Making every board safe, in a way that cancellation cannot interrupt."""

from __future__ import annotations

import asyncio
import logging

from j5aio.boards.board import Board

__all__ = ["SAFE_STATE_TIMEOUT", "make_all_safe_uncancellably"]

LOGGER = logging.getLogger(__name__)

#: How long making every board safe may take before we give up waiting, in seconds.
SAFE_STATE_TIMEOUT = 5.0


async def make_all_safe_uncancellably(timeout: float = SAFE_STATE_TIMEOUT) -> None:
    """Make every board safe, finishing even if the caller is cancelled meanwhile.

    The work runs in a task of its own, which no cancellation of the caller reaches
    (a plain ``asyncio`` cancellation breaks through an anyio shield, so a shield alone
    is not enough). If the caller is cancelled while waiting, it keeps waiting until the
    boards are safe and then re-raises the cancellation. Errors from individual boards
    are logged, never raised: they must not hide the reason the program is stopping.

    :param timeout: give up waiting after this many seconds (a board that hangs must not
        keep a stopping program alive).
    """
    task = asyncio.ensure_future(asyncio.wait_for(Board.make_all_safe(), timeout))
    cancelled = False
    while not task.done():
        try:
            await asyncio.shield(task)
        except asyncio.CancelledError:
            if task.done():
                break
            cancelled = True
        except Exception:
            break
    exc = task.exception() if not task.cancelled() else None
    if isinstance(exc, TimeoutError):
        LOGGER.error("Boards took longer than %.1f s to become safe; gave up waiting.", timeout)
    elif exc is not None:
        LOGGER.error("Could not make the boards safe: %r", exc)
    if cancelled:
        raise asyncio.CancelledError

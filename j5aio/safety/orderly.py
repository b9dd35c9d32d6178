"""The orderly async path: every set-up board made safe through its own async methods.

A robot on its way out and the sync facade's shutdown use this first
(:func:`make_all_safe_uncancellably`); each board made safe here is settled in the
registry, so that the rescue, which runs after it anyway, sends again silently.
"""

from __future__ import annotations

import asyncio
import logging
from typing import TYPE_CHECKING

import anyio

from j5aio.backends.safe_state_pass import safe_state_pass
from j5aio.safety import registry

if TYPE_CHECKING:
    from j5aio.boards.board import Board

__all__ = ["SAFE_STATE_TIMEOUT", "make_all_safe", "make_all_safe_uncancellably"]

LOGGER = logging.getLogger("j5aio.safety")
#: Where a board's failure in the orderly pass is logged (the name teams' settings know).
_BOARD_LOGGER = logging.getLogger("j5aio.boards.board")

#: How long making every board safe may take before we give up waiting, in seconds.
SAFE_STATE_TIMEOUT = 5.0


async def make_all_safe() -> list[BaseException]:
    """Make every set-up board safe, all at once (those that power the others last).

    A board that fails to become safe does not stop the others: its error is logged and
    returned, so that the caller can decide what to do with it.

    :returns: the errors raised by boards that could not be made safe.
    """
    failures: list[BaseException] = []

    async def make_one_safe(board: Board) -> None:
        try:
            await board.make_safe()
        except Exception as exc:
            _BOARD_LOGGER.error("Could not make %s safe: %s", board, exc)
            failures.append(exc)
        else:
            registry.mark_settled(board)

    # Within the pass, a lost board that has come back is looked for once more, whatever
    # its reconnection rate limit, so that it is stopped too.
    boards = list(registry.SET_UP)
    with safe_state_pass():
        for last in (False, True):  # the boards that power the others last
            async with anyio.create_task_group() as group:
                for board in boards:
                    if board.MAKE_SAFE_LAST is last:
                        group.start_soon(make_one_safe, board)
    return failures


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
    from j5aio.boards.board import Board  # its make_all_safe: a kit may override it

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

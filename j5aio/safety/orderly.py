"""The orderly async path: every set-up board made safe through its own async methods.

A robot on its way out and the sync facade's shutdown use this first
(:func:`make_all_safe_uncancellably`); each board made safe here is settled in the
registry, so that the rescue, which runs after it anyway, sends again silently.

:func:`make_all_safe_uncancellably` runs the pass through
:meth:`Board.make_all_safe <j5aio.boards.board.Board.make_all_safe>`, so that a kit that
replaces that method is obeyed. This module sits below the boards and does not import
them: the Board class hands it that call when it is defined (:func:`run_pass_through`).
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Awaitable, Callable
from typing import TYPE_CHECKING

import anyio

from j5aio.safety import registry
from j5aio.safety.safe_state_pass import safe_state_pass

if TYPE_CHECKING:
    from j5aio.boards.board import Board

__all__ = [
    "SAFE_STATE_TIMEOUT",
    "make_all_safe",
    "make_all_safe_uncancellably",
    "run_pass_through",
]

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


#: The call that runs the whole pass for :func:`make_all_safe_uncancellably`:
#: :func:`make_all_safe` until the Board class hands over its own (see the module's help).
_whole_pass: Callable[[], Awaitable[list[BaseException]]] = make_all_safe


def run_pass_through(whole_pass: Callable[[], Awaitable[list[BaseException]]]) -> None:
    """Make :func:`make_all_safe_uncancellably` run the pass by calling ``whole_pass()``.

    :mod:`j5aio.boards.board` calls it once, with a function that calls
    :meth:`Board.make_all_safe <j5aio.boards.board.Board.make_all_safe>` as it is then.

    :raises TypeError: ``whole_pass`` is not callable.
    """
    global _whole_pass
    if not callable(whole_pass):
        raise TypeError(f"the safe-state pass must be a callable, not {whole_pass!r}")
    _whole_pass = whole_pass


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
    task = asyncio.ensure_future(asyncio.wait_for(_whole_pass(), timeout))
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

"""The one registry of boards: which are open, which are set up, which were made safe.

Every board made is *open* here until it is closed (:func:`track`, :func:`untrack`);
the rescue (:mod:`j5aio.safety.rescue`) makes the open boards safe however the program
ends. Boards that are *set up* (:data:`SET_UP`, which is
:attr:`Board.BOARDS <j5aio.boards.board.Board.BOARDS>`) are those the orderly path
(:mod:`j5aio.safety.orderly`) makes safe. A board made safe in order is *settled*: the
rescue then sends its safe state again without a log line.

Game over seals the registry (:func:`begin_game_over`): from then on a board cannot be
opened, so a program cannot drive again before the process ends.

A board opened while an event loop runs is made safe when that loop ends: the rescue
asks to be told of each such loop (:func:`on_board_in_loop`) when it is imported, which
importing :mod:`j5aio.safety` (and so any of its modules) does first. The registry
imports nothing of the rescue, which reads it.
"""

from __future__ import annotations

import asyncio
import contextlib
import threading
from collections.abc import Callable
from typing import TYPE_CHECKING, Final

from j5aio.errors import GameOverError

if TYPE_CHECKING:
    from j5aio.boards.board import Board

__all__ = [
    "GAME_OVER_WAIT",
    "SET_UP",
    "begin_game_over",
    "end_game_over",
    "game_over_begun",
    "mark_settled",
    "on_board_in_loop",
    "open_boards",
    "track",
    "untrack",
    "wait_for_game_over",
]

#: The most seconds a program that ends during game over waits for game over to end it.
GAME_OVER_WAIT: Final = 5.0

_lock = threading.RLock()
#: Every board opened and not closed -> the event loop it was opened in (None: none ran).
_open: dict[Board, asyncio.AbstractEventLoop | None] = {}
#: Boards made safe in order since they were opened (no log line if the net sends again).
_settled: set[Board] = set()
#: Every board that is set up and not yet closed (``Board.BOARDS`` is this set).
SET_UP: Final[set[Board]] = set()
#: Set when game over begins: from then on no board may be opened.
_game_over = threading.Event()
#: Set when game over has finished (the process is ending).
_game_over_done = threading.Event()
#: Told of the event loop each board is opened in (see :func:`on_board_in_loop`).
_loop_watchers: list[Callable[[asyncio.AbstractEventLoop], None]] = []


# -- which boards are open ---------------------------------------------------------------


def on_board_in_loop(watcher: Callable[[asyncio.AbstractEventLoop], None]) -> None:
    """Call ``watcher(loop)`` each time a board is opened while ``loop`` runs, in that loop.

    The rescue (:func:`j5aio.safety.rescue.watch`) is told this way, so that it makes a
    loop's boards safe when the loop ends. A watcher given twice is called once.

    :raises TypeError: ``watcher`` is not callable.
    """
    if not callable(watcher):
        raise TypeError(f"a loop watcher must be a callable, not {watcher!r}")
    with _lock:
        if watcher not in _loop_watchers:
            _loop_watchers.append(watcher)


def track(board: Board) -> None:
    """Remember ``board`` as opened (boards call this when they are made).

    The event loop running now, if any, is the board's: when it finishes, the board is
    made safe and closed.

    :raises ~j5aio.errors.GameOverError: the match is over (the board's port is closed
        at once: after game over nothing may drive a board again).
    """
    try:
        loop: asyncio.AbstractEventLoop | None = asyncio.get_running_loop()
    except RuntimeError:
        loop = None
    with _lock:
        sealed = _game_over.is_set()
        if not sealed:
            _open[board] = loop
            _settled.discard(board)
    if sealed:
        close_now = getattr(board.backend, "close_now", None)
        if close_now is not None:
            with contextlib.suppress(Exception):
                close_now()
        raise GameOverError(
            f"the match is over: {board} cannot be opened after game over (the program "
            "is ending with every board safe)"
        )
    if loop is not None:
        with _lock:
            watchers = list(_loop_watchers)
        for watcher in watchers:
            watcher(loop)


def untrack(board: Board) -> None:
    """Forget ``board``: it has been closed cleanly."""
    with _lock:
        _open.pop(board, None)
        _settled.discard(board)


def mark_settled(board: Board) -> None:
    """Note that ``board`` was made safe in order (the net then sends again silently)."""
    with _lock:
        if board in _open:
            _settled.add(board)


def open_boards() -> list[Board]:
    """Every board opened and not yet closed."""
    with _lock:
        return list(_open)


# -- game over ---------------------------------------------------------------------------


def begin_game_over() -> None:
    """The match has ended: from now on opening a board raises, and the program's end waits.

    The match timer calls this before it makes the boards safe, so that a program cannot
    open fresh links and drive again before the process ends. A program that ends
    meanwhile (an unhandled exception, the end of its code) waits for game over to end
    the process, so that it ends with "Game over" and status 0, not a traceback.
    """
    with _lock:
        _game_over.set()


def game_over_begun() -> bool:
    """Whether the match has ended (:func:`begin_game_over` was called)."""
    return _game_over.is_set()


def end_game_over() -> None:
    """Game over has finished (its process-ending call returned: only in tests)."""
    _game_over_done.set()


def wait_for_game_over(timeout: float = GAME_OVER_WAIT) -> bool:
    """If game over has begun, wait (at most ``timeout`` s) for it to end the process.

    :returns: whether game over had begun.
    """
    if not _game_over.is_set():
        return False
    _game_over_done.wait(timeout)
    return True


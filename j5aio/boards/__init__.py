"""Boards: groups of components, and groups of boards."""

from typing import TYPE_CHECKING

from j5aio._lazy import lazy_exports

if TYPE_CHECKING:
    from j5aio.boards.board import Board as Board
    from j5aio.boards.board_group import BoardGroup as BoardGroup

if not TYPE_CHECKING:  # type checkers see the names imported above; __all__ is the table's
    __getattr__, __dir__ = lazy_exports(
        __name__,
        {
            "j5aio.boards.board": ["Board"],
            "j5aio.boards.board_group": ["BoardGroup"],
        },
    )

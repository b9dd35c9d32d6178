"""Boards: groups of components, and groups of boards."""

from typing import TYPE_CHECKING

from j5aio._lazy import lazy_exports

if TYPE_CHECKING:
    from j5aio.boards.board import Board
    from j5aio.boards.board_group import BoardGroup

__all__ = ["Board", "BoardGroup"]

if not TYPE_CHECKING:  # the names are imported above for type checkers
    __getattr__, __dir__ = lazy_exports(
        __name__,
        {
            "j5aio.boards.board": ["Board"],
            "j5aio.boards.board_group": ["BoardGroup"],
        },
    )

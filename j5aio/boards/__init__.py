"""Boards: groups of components, and groups of boards."""

from j5aio.boards.board import Board
from j5aio.boards.board_group import BoardGroup

__all__ = ["Board", "BoardGroup"]

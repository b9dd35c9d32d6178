"""A board class that a test names by its import path, and imports only when it must."""

from __future__ import annotations

from collections.abc import Sequence

from j5aio.boards.board import Board

from .conftest import LampBackend, LampBoard


class LazyLampBoard(LampBoard):
    """A generation of the lamp board whose class is named by its path."""


class LazyLampBackend(LampBackend):
    board = LazyLampBoard

    @classmethod
    async def discover(cls) -> Sequence[Board]:
        return [LazyLampBoard("L", cls())]


NOT_A_BOARD = "a lamp"

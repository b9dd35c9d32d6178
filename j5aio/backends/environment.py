"""Environment: the backend to use for each kind of board, in one setting."""

from __future__ import annotations

from typing import TypeVar

from j5aio.backends.backend import Backend
from j5aio.boards.board import Board
from j5aio.boards.board_group import BoardGroup

__all__ = ["Environment"]

BoardT = TypeVar("BoardT", bound=Board)


class Environment:
    """A set of backends that work together: one backend per kind of board.

    The same robot code runs on the console, on real hardware or on the simulated kit by
    handing it a different environment.

    :param name: a name to show to people, e.g. ``"HardwareEnvironment"``.
    """

    def __init__(self, name: str) -> None:
        self.name = name
        self.board_backend_mapping: dict[type[Board], type[Backend]] = {}

    @property
    def supported_boards(self) -> set[type[Board]]:
        """The kinds of board this environment has a backend for."""
        return set(self.board_backend_mapping)

    def register_backend(self, backend: type[Backend]) -> None:
        """Use ``backend`` for the kind of board it drives.

        :raises RuntimeError: this environment already has a backend for that board.
        """
        board = backend.board
        existing = self.board_backend_mapping.get(board)
        if existing is not None:
            raise RuntimeError(
                f"{self.name} already uses {existing.__name__} for {board.__name__}; "
                f"cannot register {backend.__name__} for it too.",
            )
        self.board_backend_mapping[board] = backend

    def get_backend(self, board: type[Board]) -> type[Backend]:
        """Return the backend this environment uses for ``board``.

        :raises NotImplementedError: the environment has no backend for that board.
        """
        try:
            return self.board_backend_mapping[board]
        except KeyError:
            known = ", ".join(sorted(b.__name__ for b in self.board_backend_mapping)) or "none"
            raise NotImplementedError(
                f"{self.name} does not support {board.__name__}; it supports: {known}",
            ) from None

    async def get_board_group(self, board: type[BoardT]) -> BoardGroup[BoardT]:
        """Find every ``board`` through this environment's backend for it.

        :raises NotImplementedError: the environment has no backend for that board.
        """
        return await BoardGroup.get_board_group(board, self.get_backend(board))

    def merge(self, other: Environment) -> None:
        """Add every board-to-backend mapping of ``other`` to this environment.

        :raises RuntimeError: both environments have a backend for the same board; nothing
            is merged.
        """
        common = self.supported_boards & other.supported_boards
        if common:
            names = ", ".join(sorted(board.__name__ for board in common))
            raise RuntimeError(
                f"cannot merge {other.name} into {self.name}: both have a backend for "
                f"{names}. Register the backend you want by hand instead.",
            )
        self.board_backend_mapping.update(other.board_backend_mapping)

    def __str__(self) -> str:
        return self.name

    def __repr__(self) -> str:
        return f"Environment({self.name!r})"

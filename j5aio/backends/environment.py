"""Environment: the backend to use for each kind of board, in one setting."""

from __future__ import annotations

from collections.abc import Iterable
from typing import TypeVar

from j5aio.backends.backend import Backend
from j5aio.boards.board import Board
from j5aio.boards.board_group import BoardGroup

__all__ = ["Environment"]

BoardT = TypeVar("BoardT", bound=Board)


class Environment:
    """A set of backends that work together: the backends of each kind of board.

    The same robot code runs on the console, on real hardware or on the simulated kit by
    handing it a different environment.

    Usually one backend drives each board class. A board family with several
    generations (the SR power board's USB firmware 3 and serial firmware 4, say) has one
    backend per generation: register the later ones with ``alongside=True``, or give each
    generation a subclass of the family's board class. :meth:`get_board_group` gathers
    the boards of every backend registered for the class asked for or a subclass of it.

    :param name: a name to show to people, e.g. ``"HardwareEnvironment"``.
    :param gather: find a family's boards through every backend registered for it (as
        on hardware); if false, through the first one only (the console environment,
        where every backend makes up one board).
    """

    def __init__(self, name: str, *, gather: bool = True) -> None:
        self.name = name
        #: Whether :meth:`get_board_group` gathers the boards of every generation.
        self.gather = gather
        #: The first backend registered for each board class.
        self.board_backend_mapping: dict[type[Board], type[Backend]] = {}
        #: Every backend registered, in order (several may drive one board family).
        self.backends: list[type[Backend]] = []

    @classmethod
    def from_backends(
        cls, name: str, backends: Iterable[type[Backend]], *, gather: bool = True
    ) -> Environment:
        """Make an environment of ``backends``, later generations registered alongside.

        :raises RuntimeError: a backend is listed twice.
        """
        environment = cls(name, gather=gather)
        for backend in backends:
            environment.register_backend(backend, alongside=True)
        return environment

    @property
    def supported_boards(self) -> set[type[Board]]:
        """The kinds of board this environment has a backend for."""
        return set(self.board_backend_mapping)

    def register_backend(self, backend: type[Backend], *, alongside: bool = False) -> None:
        """Use ``backend`` for the kind of board it drives.

        :param alongside: ``backend`` drives another generation of a board class that
            already has a backend here: use both, and find boards through each.
        :raises RuntimeError: this environment already has ``backend``, or already has a
            backend for its board and ``alongside`` is false.
        """
        board = backend.board
        existing = self.board_backend_mapping.get(board)
        if backend in self.backends or (existing is not None and not alongside):
            shown = existing if existing is not None else backend
            raise RuntimeError(
                f"{self.name} already uses {shown.__name__} for {board.__name__}; "
                f"cannot register {backend.__name__} for it too (pass alongside=True "
                "if it drives another generation of the board).",
            )
        self.board_backend_mapping.setdefault(board, backend)
        self.backends.append(backend)

    def get_backend(self, board: type[Board]) -> type[Backend]:
        """Return the (first) backend this environment uses for ``board``.

        :raises NotImplementedError: the environment has no backend for that board.
        """
        try:
            return self.board_backend_mapping[board]
        except KeyError:
            raise NotImplementedError(self._unsupported(board)) from None

    def backends_for(self, board: type[Board]) -> tuple[type[Backend], ...]:
        """Return every backend for ``board`` or a subclass of it, in registration order.

        :raises NotImplementedError: the environment has no backend for such a board.
        """
        found = tuple(backend for backend in self.backends if issubclass(backend.board, board))
        if not found:
            raise NotImplementedError(self._unsupported(board))
        return found

    def _unsupported(self, board: type[Board]) -> str:
        known = ", ".join(sorted(b.__name__ for b in self.board_backend_mapping)) or "none"
        return f"{self.name} does not support {board.__name__}; it supports: {known}"

    async def get_board_group(self, board: type[BoardT]) -> BoardGroup[BoardT]:
        """Find every ``board`` through each backend this environment has for it.

        Boards of every generation (backends for ``board`` or a subclass) are gathered
        into one group.

        :raises NotImplementedError: the environment has no backend for that board.
        """
        backends = self.backends_for(board)
        if not self.gather:
            backends = (self.board_backend_mapping.get(board, backends[0]),)
        return await BoardGroup.get_board_group(board, backends)

    def merge(self, other: Environment) -> None:
        """Add every backend of ``other`` to this environment.

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
        self.backends.extend(other.backends)

    def __str__(self) -> str:
        return self.name

    def __repr__(self) -> str:
        return f"Environment({self.name!r})"

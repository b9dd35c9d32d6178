"""Environment: the backend to use for each kind of board, in one setting."""

from __future__ import annotations

import sys
from collections.abc import Callable, Iterable, Iterator
from typing import TypeVar

from j5aio.backends.backend import Backend
from j5aio.boards.board import Board
from j5aio.boards.board_group import BoardGroup
from j5aio.import_paths import check_import_path, import_class

__all__ = ["BackendLoader", "Environment"]

BoardT = TypeVar("BoardT", bound=Board)

BackendLoader = Callable[[], type[Backend]]
"""Imports and returns a backend class (see :meth:`Environment.register_lazily`)."""


class _Slot:
    """One registered backend: known, or to be loaded the first time it is needed."""

    __slots__ = ("_backend", "_board", "idle", "load")

    def __init__(
        self,
        board: type[Board] | str,
        backend: type[Backend] | None = None,
        load: BackendLoader | None = None,
        idle: Callable[[], bool] | None = None,
    ) -> None:
        # The board class the backend drives (the one declared, until it is loaded), or
        # its import path until it is first needed.
        self._board = board
        self._backend = backend
        self.load = load
        self.idle = idle

    @property
    def board(self) -> type[Board]:
        """The board class (imported the first time, if it was given by its path)."""
        if isinstance(self._board, str):
            board = import_class(self._board, "the board of a backend registered lazily")
            if not issubclass(board, Board):
                raise TypeError(f"{self._board} is not a Board subclass")
            self._board = board
        return self._board

    @board.setter
    def board(self, board: type[Board]) -> None:
        self._board = board

    def declares(self, board: type[Board], path: str) -> bool:
        """Whether the board is ``board`` (whose import path is ``path``), importing nothing."""
        return self._board == path if isinstance(self._board, str) else self._board is board

    def idle_unloaded(self) -> bool:
        """Whether the board class is not imported yet and the backend would find nothing.

        Such a slot is passed over without importing its board to learn its class.
        """
        return isinstance(self._board, str) and self.idle is not None and self.idle()

    def backend(self) -> type[Backend]:
        if self._backend is None:
            assert self.load is not None
            backend = self.load()
            if not (isinstance(backend, type) and issubclass(backend, Backend)):
                raise TypeError(f"the backend loaded for {self.board.__name__} is not a Backend")
            if not issubclass(backend.board, self.board):
                raise TypeError(
                    f"the backend {backend.__name__} loaded for {self.board.__name__} drives "
                    f"{backend.board.__name__}"
                )
            self._backend, self.board, self.load = backend, backend.board, None
        return self._backend


class Environment:
    """A set of backends that work together: the backends of each kind of board.

    The same robot code runs on the console, on real hardware or on the simulated kit by
    handing it a different environment.

    Usually one backend drives each board class. A board family with several
    generations (the SR power board's USB firmware 3 and serial firmware 4, say) has one
    backend per generation: register the later ones with ``alongside=True``, or give each
    generation a subclass of the family's board class. :meth:`get_board_group` gathers
    the boards of every backend registered for the class asked for or a subclass of it.

    A backend may be registered by the board class it drives and a function that imports
    it (:meth:`register_lazily`): it is imported the first time a board of its class is
    asked for, so a program imports the backends of the boards it uses only (the
    hardware and simulated environments register every board kind's backend this way).

    :param name: a name to show to people, e.g. ``"HardwareEnvironment"``.
    :param gather: find a family's boards through every backend registered for it (as
        on hardware); if false, through the first one only (the console environment,
        where every backend makes up one board).
    """

    def __init__(self, name: str, *, gather: bool = True) -> None:
        self.name = name
        #: Whether :meth:`get_board_group` gathers the boards of every generation.
        self.gather = gather
        self._slots: list[_Slot] = []

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
    def board_backend_mapping(self) -> dict[type[Board], type[Backend]]:
        """The first backend registered for each board class (a new dict: loads them all)."""
        mapping: dict[type[Board], type[Backend]] = {}
        for backend in self.backends:
            mapping.setdefault(backend.board, backend)
        return mapping

    @property
    def backends(self) -> list[type[Backend]]:
        """Every backend registered, in order (a new list: loads them all)."""
        return [slot.backend() for slot in self._slots]

    @property
    def supported_boards(self) -> set[type[Board]]:
        """The kinds of board this environment has a backend for (loading none of them)."""
        return {slot.board for slot in self._slots}

    def _has_backend_for(self, board: type[Board]) -> bool:
        """Whether ``board`` is in :attr:`supported_boards`, importing no board class to tell."""
        path = f"{board.__module__}:{board.__qualname__}"
        return any(slot.declares(board, path) for slot in self._slots)

    def register_backend(self, backend: type[Backend], *, alongside: bool = False) -> None:
        """Use ``backend`` for the kind of board it drives.

        :param alongside: ``backend`` drives another generation of a board class that
            already has a backend here: use both, and find boards through each.
        :raises RuntimeError: this environment already has ``backend``, or already has a
            backend for its board and ``alongside`` is false.
        """
        board = backend.board
        # Only a backend registered for this board class can be the same backend or the
        # board's first one.
        related = [slot for slot in self._slots if slot.board is board]
        known = [slot.backend() for slot in related]
        existing = next((b for b in known if b.board is board), None)
        if backend in known or (existing is not None and not alongside):
            shown = existing if existing is not None else backend
            raise RuntimeError(
                f"{self.name} already uses {shown.__name__} for {board.__name__}; "
                f"cannot register {backend.__name__} for it too (pass alongside=True "
                "if it drives another generation of the board).",
            )
        self._slots.append(_Slot(board, backend))

    def register_lazily(
        self,
        board: type[Board],
        load: BackendLoader,
        *,
        idle: Callable[[], bool] | None = None,
    ) -> None:
        """Use the backend ``load()`` returns for ``board``, importing it on first use.

        It is registered alongside any other backend for ``board`` (as
        :meth:`register_backend` does with ``alongside=True``), and loaded the first time
        a board it may drive is asked for, or :attr:`backends` or
        :attr:`board_backend_mapping` is read.

        :param board: the board class the backend drives (its ``board``). Should it
            drive a subclass of ``board``, it is known by that subclass once loaded.
        :param load: imports and returns the backend; what it returns is checked to be
            a :class:`~j5aio.backends.backend.Backend` driving ``board`` or a subclass
            (:class:`TypeError` otherwise).
        :param idle: says, when :meth:`get_board_group` runs, that the backend would
            find no board now (the simulated kit has none of its boards, say): it is then
            not asked, nor loaded if it is not yet (unless no backend for the board is
            active: the group then holds the first backend, with no boards).
        :raises TypeError: ``board`` is not a Board subclass, or ``load`` is not callable.
        """
        if not (isinstance(board, type) and issubclass(board, Board)):
            raise TypeError(f"board must be a Board subclass, not {board!r}")
        if not callable(load):
            raise TypeError(f"load must be callable, not {type(load).__name__}")
        self._slots.append(_Slot(board, load=load, idle=idle))

    def _register_lazily_by_path(
        self, board: str, load: BackendLoader, *, idle: Callable[[], bool] | None = None
    ) -> None:
        """As :meth:`register_lazily`, the board class named by its import path.

        The board's module is imported the first time a board of a class it may be a
        subclass of is asked for, unless ``idle`` says then that the backend would find
        nothing (a simulated kit without such boards never imports their classes).
        """
        check_import_path(board, "the board of a backend registered lazily")
        if not callable(load):
            raise TypeError(f"load must be callable, not {type(load).__name__}")
        self._slots.append(_Slot(board, load=load, idle=idle))

    def get_backend(self, board: type[Board]) -> type[Backend]:
        """Return the (first) backend this environment uses for ``board``.

        :raises NotImplementedError: the environment has no backend for that board.
        """
        for slot in self._slots:
            if slot.board is board and slot.backend().board is board:
                return slot.backend()
        raise NotImplementedError(self._unsupported(board))

    def backends_for(self, board: type[Board]) -> tuple[type[Backend], ...]:
        """Return every backend for ``board`` or a subclass of it, in registration order.

        :raises NotImplementedError: the environment has no backend for such a board.
        """
        found = tuple(self._backends_for(board, active_only=False))
        if not found:
            raise NotImplementedError(self._unsupported(board))
        return found

    def _backends_for(self, board: type[Board], *, active_only: bool) -> Iterator[type[Backend]]:
        for slot in self._slots:
            if active_only and slot.idle_unloaded():
                continue
            if not issubclass(slot.board, board):
                continue
            if active_only and slot.idle is not None and slot.idle():
                continue
            backend = slot.backend()
            if issubclass(backend.board, board):
                yield backend

    def might_find(self, board: type[Board]) -> bool:
        """Whether :meth:`get_board_group` would ask any backend for ``board`` now.

        False when the environment has no backend for ``board`` (or a subclass), or when
        every such backend registered with ``idle`` says it would find nothing now; it
        loads no backend to tell.
        """
        return any(
            not slot.idle_unloaded()
            and issubclass(slot.board, board)
            and (slot.idle is None or not slot.idle())
            for slot in self._slots
        )

    def _might_find_named(self, path: str) -> bool:
        """:meth:`might_find` for the board class at ``path``, imported only if it may be found.

        While its module is not imported, no board class registered as a class can be it
        or a subclass of it (such a class would have imported it): only a backend whose
        board is still named by its path, and is not idle, may find one; the class is
        imported then to ask.
        """
        module = check_import_path(path, "a board class").partition(":")[0]
        if module not in sys.modules and all(
            not isinstance(slot._board, str) or slot.idle_unloaded() for slot in self._slots
        ):
            return False
        board = import_class(path, "a board class")
        if not issubclass(board, Board):
            raise TypeError(f"{path} is not a Board subclass")
        return self.might_find(board)

    def _unsupported(self, board: type[Board]) -> str:
        known = ", ".join(sorted({slot.board.__name__ for slot in self._slots})) or "none"
        return f"{self.name} does not support {board.__name__}; it supports: {known}"

    async def get_board_group(self, board: type[BoardT]) -> BoardGroup[BoardT]:
        """Find every ``board`` through each backend this environment has for it.

        Boards of every generation (backends for ``board`` or a subclass) are gathered
        into one group. A backend registered lazily whose ``idle`` says it would find
        nothing now is left out (and not imported).

        :raises NotImplementedError: the environment has no backend for that board.
        """
        if not self.gather:
            first = self._first_for(board)
            return await BoardGroup.get_board_group(board, (first,))
        backends = tuple(self._backends_for(board, active_only=True))
        if not backends:  # each would find nothing now: a group of the first, not asked
            slot = next((slot for slot in self._slots if issubclass(slot.board, board)), None)
            if slot is None:
                raise NotImplementedError(self._unsupported(board))
            # (its backend is imported only if the group is looked in again, or asked)
            return BoardGroup._not_looked_in(board, lambda: (slot.backend(),))
        return await BoardGroup.get_board_group(board, backends)

    def _first_for(self, board: type[Board]) -> type[Backend]:
        try:
            return self.get_backend(board)
        except NotImplementedError:
            return self.backends_for(board)[0]

    def merge(self, other: Environment) -> None:
        """Add every backend of ``other`` to this environment (unloaded ones stay so).

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
        self._slots.extend(other._slots)

    def __str__(self) -> str:
        return self.name

    def __repr__(self) -> str:
        return f"Environment({self.name!r})"

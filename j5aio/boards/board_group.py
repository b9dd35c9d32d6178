"""BoardGroup: every connected board of one type, found through its backend(s)."""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from typing import TYPE_CHECKING, Any, Generic, TypeVar

from j5aio.boards.board import Board
from j5aio.errors import CommunicationError
from j5aio.safety import hooks as safety_hooks

if TYPE_CHECKING:
    from j5aio.backends.backend import Backend

__all__ = ["BoardGroup"]

BoardT = TypeVar("BoardT", bound=Board)


class BoardGroup(Generic[BoardT]):
    """The boards of one type that a backend can reach, ordered by serial number.

    Create one with :meth:`get_board_group`::

        motor_boards = await BoardGroup.get_board_group(MotorBoard, SRV4MotorBoardHardwareBackend)
        motor_boards["SR0A1B"].motors[0]   # by serial number
        motor_boards[0]                    # or by position

    :param board_type: the class of board in this group.
    :param backend_class: the backend that finds and drives the boards.
    :param ports: explicit ports to attach to as well as discovery (serial backends).
    """

    def __init__(
        self,
        board_type: type[BoardT],
        backend_class: type[Backend] | Sequence[type[Backend]],
        *,
        ports: Sequence[str] = (),
    ) -> None:
        backends = _checked(board_type, _backend_tuple(backend_class))
        self._board_type = board_type
        self._backend_classes = backends
        # (set by _not_looked_in: loads the backends the first time they are needed)
        self._load_backends: Callable[[], tuple[type[Backend], ...]] | None = None
        self._ports = tuple(ports)
        self._boards: dict[str, BoardT] = {}
        #: Said when a board is looked up in the group while it is empty: which other
        #: groups have boards, say (:class:`~j5aio.kit.KitRobot` fills it in).
        self.empty_hint: str | None = None

    @classmethod
    async def get_board_group(
        cls,
        board: type[BoardT],
        backend: type[Backend] | Sequence[type[Backend]],
        *,
        ports: Sequence[str] = (),
    ) -> BoardGroup[BoardT]:
        """Find every board of class ``board`` that ``backend`` can reach.

        The parameters have j5's names, so ``get_board_group(board=..., backend=...)``
        works as it did there.

        :param board: the class of board wanted, e.g. ``PowerBoard``.
        :param backend: the backend to find and drive them with, or several (one per
            generation of the board: their boards are gathered into one group).
        :param ports: explicit ports (device paths or pyserial URLs) to attach to, on top
            of discovery, for unusual adapters and simulators; they are attached with the
            first backend.
        :returns: the group, ordered by serial number.
        :raises TypeError: a backend drives another kind of board, or none was given.
        :raises CommunicationError: two boards report the same serial number.
        """
        group = cls(board, backend, ports=ports)
        await group.update_boards()
        return group

    @classmethod
    def _not_looked_in(
        cls, board_type: type[BoardT], load_backends: Callable[[], tuple[type[Backend], ...]]
    ) -> BoardGroup[BoardT]:
        """An empty group whose backends are imported the first time they are needed.

        An environment makes one for a board it knows would find none now, so that the
        backend is imported only if a program looks again (:meth:`update_boards`) or asks
        for it. ``load_backends`` returns them; it is called once, and each is checked
        then to drive a ``board_type`` (:class:`TypeError` otherwise).
        """
        group = cls.__new__(cls)
        group._board_type = board_type
        group._backend_classes = ()
        group._load_backends = load_backends
        group._ports = ()
        group._boards = {}
        group.empty_hint = None
        return group

    def _backends(self) -> tuple[type[Backend], ...]:
        """The backends, loaded now if they were left to be loaded when first needed."""
        if self._load_backends is not None:
            self._backend_classes = _checked(self._board_type, self._load_backends())
            self._load_backends = None
        return self._backend_classes

    @classmethod
    def of_groups(
        cls, board_type: type[BoardT], groups: Sequence[BoardGroup[Any]]
    ) -> BoardGroup[Any]:
        """One group of the boards of ``groups``, ordered by serial number.

        Looking again (:meth:`update_boards`) asks every backend of every group.

        :param board_type: a class every board of the groups is an instance of.
        :param groups: the groups, each already looked in.
        :raises TypeError: a group's backend drives another kind of board.
        """
        if any(group._load_backends is not None for group in groups):
            # (a group not looked in keeps its backends unloaded: so does the whole)
            combined: BoardGroup[Any] = cls._not_looked_in(board_type, lambda: _joined(groups))
        else:
            combined = cls(board_type, _joined(groups))
        found = {board.serial_number: board for group in groups for board in group}
        combined._boards = dict(sorted(found.items()))
        return combined

    async def update_boards(self) -> None:
        """Look for boards again, so that boards connected since are included.

        :raises CommunicationError: two boards report the same serial number.
        """
        safety_hooks.install()  # a program's way to its boards: it gets the safety hooks
        found: list[tuple[Board, type[Backend]]] = []
        for backend in self._backends():
            found.extend((board, backend) for board in await backend.discover())
        for port in self._ports:
            first = self._backends()[0]
            found.append((await first.attach(port), first))
        boards: dict[str, BoardT] = {}
        finders: dict[str, type[Backend]] = {}
        for board, backend in sorted(found, key=lambda item: item[0].serial_number):
            if not isinstance(board, self._board_type):  # pragma: no cover - backend bug
                raise TypeError(f"{backend.__name__} returned {board!r}")
            if board.serial_number in boards and boards[board.serial_number] is not board:
                raise CommunicationError(
                    f"two {self._board_type.__name__}s report serial number "
                    f"{board.serial_number!r} (found by {finders[board.serial_number].__name__} "
                    f"and {backend.__name__}): a board's serial number must be unique.",
                )
            await board.setup()
            boards[board.serial_number] = board
            finders[board.serial_number] = backend
        self._boards = boards

    def singular(self) -> BoardT:
        """Return the only board in the group.

        :raises CommunicationError: there is not exactly one board.
        """
        if len(self._boards) == 1:
            return next(iter(self._boards.values()))
        found = ", ".join(self._boards) or "none"
        raise CommunicationError(
            f"expected exactly one {self._board_type.__name__} to be connected, but found "
            f"{len(self._boards)} ({found}). Check that it is plugged in and powered, or "
            "pick one by serial number.",
        )

    async def make_safe(self) -> None:
        """Make every board in the group safe."""
        for board in self._boards.values():
            await board.make_safe()

    @property
    def backend_class(self) -> type[Backend]:
        """The backend that finds and drives the boards (the first, if there are several)."""
        return self._backends()[0]

    @property
    def backend_classes(self) -> tuple[type[Backend], ...]:
        """Every backend the boards are found through (one per generation of the board)."""
        return self._backends()

    @property
    def board_type(self) -> type[BoardT]:
        """The class of board in this group."""
        return self._board_type

    @property
    def boards(self) -> list[BoardT]:
        """The boards, ordered by serial number."""
        return list(self._boards.values())

    def __len__(self) -> int:
        return len(self._boards)

    def __iter__(self) -> Iterator[BoardT]:
        return iter(list(self._boards.values()))

    def __contains__(self, serial_number: object) -> bool:
        return serial_number in self._boards

    def __getitem__(self, key: str | int) -> BoardT:
        """Return a board by serial number (``str``) or by position (``int``).

        :raises KeyError: no board has that serial number; the message lists those present.
        :raises IndexError: the position is out of range.
        :raises TypeError: the key is neither a string nor an integer.
        """
        if isinstance(key, str):
            try:
                return self._boards[key]
            except KeyError:
                present = ", ".join(self._boards) or "none"
                raise KeyError(
                    f"no {self._board_type.__name__} with serial number {key!r}; "
                    f"connected: {present}{self._hint()}",
                ) from None
        if isinstance(key, int) and not isinstance(key, bool):
            boards = self.boards
            if -len(boards) <= key < len(boards):
                return boards[key]
            raise IndexError(
                f"board index {key} is out of range: there are {len(boards)} "
                f"{self._board_type.__name__}(s){self._hint()}",
            )
        raise TypeError(
            f"look boards up by serial number (a str) or position (an int), not "
            f"{type(key).__name__}",
        )

    def _hint(self) -> str:
        return f". {self.empty_hint}" if self.empty_hint and not self._boards else ""

    def __str__(self) -> str:
        return f"Group of Boards - [{', '.join(map(str, self._boards.values()))}]"

    def __repr__(self) -> str:
        return (
            f"BoardGroup(board_type={self._board_type.__name__}, "
            f"backend_class={', '.join(b.__name__ for b in self._backends())})"
        )


def _backend_tuple(
    backend_class: type[Backend] | Sequence[type[Backend]],
) -> tuple[type[Backend], ...]:
    if isinstance(backend_class, type):
        return (backend_class,)
    backends = tuple(backend_class)
    if not backends or not all(isinstance(backend, type) for backend in backends):
        raise TypeError(
            f"backend_class must be a backend class or a non-empty sequence of them, "
            f"not {backend_class!r}",
        )
    return backends


def _checked(
    board_type: type[Board], backends: tuple[type[Backend], ...]
) -> tuple[type[Backend], ...]:
    for backend in backends:
        if not issubclass(backend.board, board_type):
            raise TypeError(
                f"{backend.__name__} drives {backend.board.__name__}, not "
                f"{board_type.__name__}: choose a backend for {board_type.__name__}.",
            )
    return backends


def _joined(groups: Sequence[BoardGroup[Any]]) -> tuple[type[Backend], ...]:
    return tuple(dict.fromkeys(b for group in groups for b in group.backend_classes))

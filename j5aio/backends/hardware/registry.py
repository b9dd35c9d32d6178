"""Which board holds each open port or USB device, so none is opened twice.

Discovery and ``attach`` go through :func:`claim`: a port that a live backend already
holds gives back that backend's board instead of being opened again, and two tasks
opening the same port at once end up with the same board. A backend calls
:func:`release` when it closes or finds its port gone.
"""

from __future__ import annotations

from collections.abc import Awaitable, Callable

import anyio

from j5aio.boards.board import Board
from j5aio.errors import CommunicationError

__all__ = ["PortInUseError", "claim", "find_serial", "held", "holder", "move", "release"]

_boards: dict[str, Board] = {}
_opening: dict[str, anyio.Event] = {}


class PortInUseError(CommunicationError):
    """The port is held by a backend of another kind (say, a Ruggeduino backend)."""


def held() -> frozenset[str]:
    """Return the keys of every port and device held now."""
    return frozenset(_boards)


def holder(key: str) -> Board | None:
    """Return the board holding ``key`` (a port path or USB device key), if any."""
    return _boards.get(key)


async def claim(key: str, backend_class: type, connect: Callable[[], Awaitable[Board]]) -> Board:
    """Return the board on ``key``, connecting it with ``connect`` unless it is already held.

    :raises PortInUseError: a backend that is not a ``backend_class`` holds ``key``.
    """
    while (opening := _opening.get(key)) is not None:
        await opening.wait()
    existing = _boards.get(key)
    if existing is not None:
        if isinstance(existing.backend, backend_class):
            return existing
        raise PortInUseError(
            f"{key} is already in use by {existing} ({type(existing.backend).__name__}); "
            f"close that board before opening the port as a {backend_class.__name__}",
        )
    done = _opening[key] = anyio.Event()
    try:
        board = await connect()
        _boards[key] = board
        return board
    finally:
        del _opening[key]
        done.set()


def release(key: str, backend: object) -> None:
    """Forget ``key`` if the board holding it is driven by ``backend``."""
    board = _boards.get(key)
    if board is not None and board.backend is backend:
        del _boards[key]


def find_serial(backend_class: type, serial_number: str) -> Board | None:
    """Return the board of ``backend_class`` with ``serial_number``, whatever its key.

    Discovery asks this first, so that a board that came back on another port (a
    replugged USB-serial adapter may get a new path) is handed back, not duplicated.
    """
    for board in _boards.values():
        if isinstance(board.backend, backend_class) and board.serial_number == serial_number:
            return board
    return None


def move(old_key: str, new_key: str, backend: object) -> None:
    """Hold ``new_key`` instead of ``old_key`` for the board driven by ``backend``.

    :raises PortInUseError: another board holds ``new_key``.
    """
    board = _boards.get(old_key)
    if board is None or board.backend is not backend or old_key == new_key:
        return
    other = _boards.get(new_key)
    if other is not None and other is not board:
        raise PortInUseError(f"{new_key} is already in use by {other}")
    del _boards[old_key]
    _boards[new_key] = board


def clear() -> None:
    """Forget every port (for tests; does not close anything)."""
    _boards.clear()

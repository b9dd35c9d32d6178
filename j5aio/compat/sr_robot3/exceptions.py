"""sr-robot3's exceptions, with its base classes, so that a team's ``except`` clauses work."""

from __future__ import annotations

import logging
import threading

from j5aio.compat._shared.errors import (
    EarlyMetadataError,
    MissingMetadataKeyError,
    WrongBoardTypeError,
)
from j5aio.errors import CommunicationError

__all__ = [
    "BoardDisconnectionError",
    "IncorrectBoardError",
    "MetadataKeyError",
    "MetadataNotReadyError",
    "disconnected",
    "end_of_match",
]

_TIMEOUT_LOGGER = logging.getLogger("sr.robot3.timeout")
_game_over = threading.Event()


class MetadataKeyError(MissingMetadataKeyError):
    """A metadata key was asked for that has no value.

    :param key: the key that was not found.
    """


class MetadataNotReadyError(EarlyMetadataError):
    """The zone, arena or mode was asked for before ``wait_start`` (the start) happened."""

    _examples = "zone, arena and mode"


class BoardDisconnectionError(IOError):
    """Talking to a board failed and could not be put right (an ``OSError``, as in sr-robot3).

    j5aio's own :class:`~j5aio.errors.CommunicationError` (a timeout, a board unplugged, a
    reply that makes no sense) reaches an sr-robot3 program as this error, with j5aio's
    error as its ``__cause__``.
    """


class IncorrectBoardError(WrongBoardTypeError):
    """A board answered with another board type than the one expected.

    :param board_type: the type the board gave.
    :param expected_type: the type expected.
    """


def disconnected(error: CommunicationError) -> BoardDisconnectionError | SystemExit:
    """What an sr-robot3 program gets for j5aio's ``error``.

    Once the match is over, every board is safe and closed and the process is ending:
    the program ends quietly, with status 0, as sr-robot3's timeout ends it
    (``SystemExit(0)``). Otherwise it is a :class:`BoardDisconnectionError`.
    """
    if _game_over.is_set():
        return SystemExit(0)
    return BoardDisconnectionError(str(error))


def end_of_match() -> None:
    """The game-over hook of a match run by sr-robot3's API: log sr-robot3's line.

    From then on a board call ends the program (see :func:`disconnected`).
    """
    _game_over.set()
    _TIMEOUT_LOGGER.info("Timeout expired: Game Over!")

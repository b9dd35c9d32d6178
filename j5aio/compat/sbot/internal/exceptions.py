"""The exceptions of sbot, with sbot's base classes so that ``except`` clauses still catch them.

- ``MetadataNotReadyError`` (a ``RuntimeError``): ``comp.zone`` or
  ``comp.is_competition`` was read before the start.
- ``MetadataKeyError`` (a ``KeyError``): the metadata lacks a key.
- ``BoardDisconnectionError``: both an ``IOError``, as in sbot, and j5aio's
  :class:`j5aio.errors.BoardDisconnectionError`.
- ``IncorrectBoardError`` (an ``IOError``): a board gave another board type.
"""

from __future__ import annotations

from j5aio.compat._shared.errors import (
    EarlyMetadataError,
    MissingMetadataKeyError,
    WrongBoardTypeError,
)
from j5aio.errors import BoardDisconnectionError as _CoreDisconnection

__all__ = [
    "BoardDisconnectionError",
    "IncorrectBoardError",
    "MetadataKeyError",
    "MetadataNotReadyError",
]


class MetadataKeyError(MissingMetadataKeyError):
    """A metadata key has no value.

    :param key: the key that was not found.
    """

    # sbot's class defines its own constructor, so its API surface lists one here.
    __init__ = MissingMetadataKeyError.__init__


class MetadataNotReadyError(EarlyMetadataError):
    """The metadata (``comp.zone``, ``comp.is_competition``) was read before the start."""

    _examples = "e.g. zone or is_competition"


class BoardDisconnectionError(_CoreDisconnection, OSError):
    """Talking to a board failed and could not be restarted.

    It is both j5aio's :class:`~j5aio.errors.BoardDisconnectionError` and an ``IOError``
    (sbot's base), so either kind of ``except`` clause catches it.
    """


class IncorrectBoardError(WrongBoardTypeError):
    """A board answered ``*IDN?`` with another board type than the one expected.

    :param board_type: the board type the board gave.
    :param expected_type: the board type expected.
    """

    # sbot's class defines its own constructor, so its API surface lists one here.
    __init__ = WrongBoardTypeError.__init__

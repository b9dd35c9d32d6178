"""The exceptions of sbot, with sbot's base classes so that ``except`` clauses still catch them.

- ``MetadataNotReadyError`` (a ``RuntimeError``): ``comp.zone`` or
  ``comp.is_competition`` was read before the start.
- ``MetadataKeyError`` (a ``KeyError``): the metadata lacks a key.
- ``BoardDisconnectionError``: both an ``IOError``, as in sbot, and j5aio's
  :class:`j5aio.errors.BoardDisconnectionError`.
- ``IncorrectBoardError`` (an ``IOError``): a board gave another board type.
"""

from __future__ import annotations

from j5aio.errors import BoardDisconnectionError as _CoreDisconnection

__all__ = [
    "BoardDisconnectionError",
    "IncorrectBoardError",
    "MetadataKeyError",
    "MetadataNotReadyError",
]


class MetadataKeyError(KeyError):
    """A metadata key has no value.

    :param key: the key that was not found.
    """

    def __init__(self, key: str) -> None:
        super().__init__(key)
        self.key = key

    def __str__(self) -> str:
        return f"Key {self.key!r} not present in metadata"


class MetadataNotReadyError(RuntimeError):
    """The metadata (``comp.zone``, ``comp.is_competition``) was read before the start."""

    def __str__(self) -> str:
        return (
            "Metadata (e.g. zone or is_competition) can only be used after"
            " wait_start has been called"
        )


class BoardDisconnectionError(_CoreDisconnection, OSError):
    """Talking to a board failed and could not be restarted.

    It is both j5aio's :class:`~j5aio.errors.BoardDisconnectionError` and an ``IOError``
    (sbot's base), so either kind of ``except`` clause catches it.
    """


class IncorrectBoardError(OSError):
    """A board answered ``*IDN?`` with another board type than the one expected.

    :param board_type: the board type the board gave.
    :param expected_type: the board type expected.
    """

    def __init__(self, board_type: str, expected_type: str) -> None:
        super().__init__(board_type, expected_type)
        self.returned_type = board_type
        self.expected_type = expected_type

    def __str__(self) -> str:
        return f"Board returned type {self.returned_type!r}, expected {self.expected_type!r}"

"""The exceptions both peers raise alike; each package subclasses them under its names."""

from __future__ import annotations

from typing import ClassVar

__all__ = ["EarlyMetadataError", "MissingMetadataKeyError", "WrongBoardTypeError"]


class MissingMetadataKeyError(KeyError):
    """A metadata key was asked for that has no value.

    :param key: the key that was not found.
    """

    def __init__(self, key: str) -> None:
        super().__init__(key)
        self.key = key

    def __str__(self) -> str:
        return f"Key {self.key!r} not present in metadata"


class EarlyMetadataError(RuntimeError):
    """The match's metadata was read before the start (``wait_start``)."""

    #: The metadata the message names, as the peer words it.
    _examples: ClassVar[str] = "zone"

    def __str__(self) -> str:
        return f"Metadata ({self._examples}) can only be used after wait_start has been called"


class WrongBoardTypeError(OSError):
    """A board answered with another board type than the one expected.

    :param board_type: the type the board gave.
    :param expected_type: the type expected.
    """

    def __init__(self, board_type: str, expected_type: str) -> None:
        super().__init__(board_type, expected_type)
        self.returned_type = board_type
        self.expected_type = expected_type

    def __str__(self) -> str:
        return f"Board returned type {self.returned_type!r}, expected {self.expected_type!r}"

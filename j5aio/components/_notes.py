"""The musical notes a piezo plays, made the first time they are asked for.

:class:`Note` is fifteen enum members, and making an enum costs a few microseconds a
member; a program that starts a robot and never buzzes a note never needs them. So it is
defined here, and :mod:`j5aio.components.piezo`, whose name it carries, gives it (and the
:data:`~j5aio.components.piezo.Pitch` alias that names it) when it is first looked up.
"""

from __future__ import annotations

from enum import Enum

__all__ = ["Note"]


class Note(float, Enum):
    """Musical notes in the sixth and seventh octaves, in hertz (with j5's values)."""

    # Documented, pickled and shown where programs find it.
    __module__ = "j5aio.components.piezo"

    C6 = 1047.0
    D6 = 1174.7
    E6 = 1318.5
    F6 = 1396.9
    G6 = 1568.0
    A6 = 1760.0
    B6 = 1975.5
    C7 = 2093.0
    D7 = 2349.3
    E7 = 2637.0
    F7 = 2793.8
    G7 = 3136.0
    A7 = 3520.0
    B7 = 3951.1
    C8 = 4186.0

    def __str__(self) -> str:
        return self.name

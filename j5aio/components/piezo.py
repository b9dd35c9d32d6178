"""Piezo sounders: a buzzer that plays a pitch for a duration."""

from __future__ import annotations

from abc import abstractmethod
from datetime import timedelta
from enum import Enum

from j5aio.components.component import Interface

__all__ = ["Note", "PiezoInterface", "Pitch"]


class Note(float, Enum):
    """Musical notes in the sixth and seventh octaves, in hertz (with j5's values)."""

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


Pitch = int | float | Note
"""A pitch: a frequency in hertz, or a :class:`Note`."""


class PiezoInterface(Interface):
    """The coroutines a backend implements to drive piezo sounders."""

    @abstractmethod
    async def buzz(self, identifier: int, duration: timedelta, pitch: float) -> None:
        """Start piezo ``identifier`` sounding ``pitch`` hertz for ``duration``.

        Returns once the board has accepted the note, not when it has finished playing.
        """
        raise NotImplementedError

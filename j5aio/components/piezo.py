"""Piezo sounders: a buzzer that plays a pitch for a duration.

(:class:`datetime.timedelta`, in which durations are given, is imported when a duration
is first handled, and :class:`Note` is made when it is first looked up: a program that
starts a robot and never buzzes does not load the one's C module or make the other's
fifteen enum members.)
"""

from __future__ import annotations

import math
import sys
from abc import abstractmethod
from typing import TYPE_CHECKING, Any, ClassVar

import anyio

from j5aio.components._checks import describe
from j5aio.components.component import Interface
from j5aio.components.identified import IdentifiedComponent

if TYPE_CHECKING:
    from j5aio._timedelta import timedelta
    from j5aio.components._notes import Note
elif "_datetime" in sys.modules:
    # Loaded already (by the program, or by the docs' build): binding it costs nothing,
    # and annotations read at run time (typing.get_type_hints) then resolve.
    from j5aio._timedelta import timedelta

__all__ = ["Duration", "Note", "Piezo", "PiezoInterface", "Pitch"]


class _Milliseconds:
    """A class attribute worth ``timedelta(milliseconds=count)``, made when it is read."""

    __slots__ = ("_count",)

    def __init__(self, count: int) -> None:
        self._count = count

    def __get__(self, instance: object, owner: type | None = None) -> timedelta:
        from j5aio._timedelta import timedelta

        return timedelta(milliseconds=self._count)


class PiezoInterface(Interface):
    """The coroutines a backend implements to drive piezo sounders.

    A backend whose board plays durations or pitches in steps other than whole
    milliseconds and whole hertz overrides :attr:`DURATION_STEP` and :attr:`PITCH_STEP`:
    :class:`Piezo` refuses a note that rounds to zero steps, before anything is sent.
    """

    if TYPE_CHECKING:
        #: The smallest duration step the board plays; a duration is rounded to a whole
        #: number of steps (half to even), and one that rounds to zero is refused.
        DURATION_STEP: ClassVar[timedelta] = timedelta(milliseconds=1)
    else:
        DURATION_STEP = _Milliseconds(1)
    #: The smallest pitch step the board plays, in hertz; rounded like the duration.
    PITCH_STEP: ClassVar[float] = 1.0

    @abstractmethod
    async def buzz(self, identifier: int, duration: timedelta, pitch: float) -> None:
        """Start piezo ``identifier`` sounding ``pitch`` hertz for ``duration``.

        Returns once the board has accepted the note, not when it has finished playing.
        """
        raise NotImplementedError


if TYPE_CHECKING:
    Duration = int | float | timedelta
    """How long to buzz: a number of seconds, or a :class:`datetime.timedelta`."""

    Pitch = int | float | Note
    """A pitch: a frequency in hertz, or a :class:`Note`."""
else:

    def __getattr__(name: str) -> Any:  # PEP 562: Note and the aliases, made when looked up
        if name == "Note":
            from j5aio.components._notes import Note

            value = Note
        elif name == "Pitch":
            value = int | float | __getattr__("Note")
        elif name == "Duration":
            from j5aio._timedelta import timedelta

            value = int | float | timedelta
        else:
            raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
        globals()[name] = value
        return value

    def __dir__() -> list[str]:
        return sorted({*globals(), *__all__})


_DURATION_ALLOWED = "a number of seconds greater than zero, or a datetime.timedelta"
_PITCH_ALLOWED = "a frequency in hertz greater than zero (an int or a float), or a Note"


class Piezo(IdentifiedComponent[PiezoInterface]):
    """A piezo sounder: a buzzer that plays one pitch at a time.

    ``await piezo.buzz(0.5, Note.A6)`` plays an A for half a second.

    :param identifier: the number of the piezo on its board.
    :param backend: the backend that drives the piezo.
    """

    __slots__ = ()

    @classmethod
    def interface_class(cls) -> type[PiezoInterface]:
        """The interface a backend implements to drive piezos: :class:`PiezoInterface`."""
        return PiezoInterface

    async def buzz(
        self, duration: int | float | timedelta, pitch: Pitch, *, blocking: bool = False
    ) -> None:
        """Play ``pitch`` for ``duration``.

        By default this returns as soon as the board has accepted the note, while the
        note is still playing. With ``blocking=True`` it also waits until the note has
        finished.

        :param duration: how long to play: a number of seconds, or a ``timedelta``.
        :param pitch: the frequency in hertz, or a :class:`Note` such as ``Note.A6``.
        :param blocking: wait until the note has finished before returning.
        :raises TypeError: ``duration`` or ``pitch`` has the wrong type (a bool is refused).
        :raises ValueError: ``duration`` or ``pitch`` is zero, negative, NaN or infinite,
            or so small that it rounds to nothing the board can play (below half of the
            backend's :attr:`PiezoInterface.DURATION_STEP` or
            :attr:`PiezoInterface.PITCH_STEP`: 0.5 ms and 0.5 Hz on the SR power board).
        :raises NotSupportedByHardwareError: (from the backend) the board cannot play
            this note, for example because it is too long.
        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        length = self._as_timedelta(duration)
        self.verify_duration(length)
        self.verify_pitch(pitch)
        from j5aio.components._notes import Note  # (loaded already if pitch is one)

        frequency = pitch if isinstance(pitch, Note) else float(pitch)
        self._check_playable(length, frequency)
        await self._backend.buzz(self._identifier, length, frequency)
        if blocking:
            await anyio.sleep(length.total_seconds())

    def _check_playable(self, duration: timedelta, frequency: float) -> None:
        """Refuse a note whose duration or pitch rounds to zero of the board's steps."""
        duration_step = self._backend.DURATION_STEP
        if round(duration / duration_step) < 1:
            raise ValueError(
                f"piezo duration {duration.total_seconds():g} s is too short for this board, "
                f"which plays whole steps of {duration_step.total_seconds():g} s: it would "
                f"round to nothing; give more than half a step",
            )
        pitch_step = self._backend.PITCH_STEP
        if round(frequency / pitch_step) < 1:
            raise ValueError(
                f"piezo pitch {frequency:g} Hz is too low for this board, which plays whole "
                f"steps of {pitch_step:g} Hz: it would round to 0 Hz (silence); give more "
                "than half a step",
            )

    @staticmethod
    def verify_pitch(pitch: Pitch) -> None:
        """Check that ``pitch`` is a frequency a piezo can play.

        :raises TypeError: ``pitch`` is not an int, a float or a :class:`Note` (a bool
            is refused too).
        :raises ValueError: ``pitch`` is zero, negative, NaN or infinite.
        """
        if isinstance(pitch, bool) or not isinstance(pitch, int | float):
            raise TypeError(f"piezo pitch must be {_PITCH_ALLOWED}; got {describe(pitch)}")
        try:
            valid = math.isfinite(pitch) and pitch > 0
        except OverflowError:  # an int too large to be a float
            valid = False
        if not valid:
            raise ValueError(f"piezo pitch must be {_PITCH_ALLOWED}; got {pitch!r}")

    @staticmethod
    def verify_duration(duration: timedelta) -> None:
        """Check that ``duration`` is a length of time a piezo can play for.

        :raises TypeError: ``duration`` is not a ``datetime.timedelta``.
        :raises ValueError: ``duration`` is zero or negative.
        """
        from j5aio._timedelta import timedelta

        if not isinstance(duration, timedelta):
            raise TypeError(
                f"piezo duration must be a datetime.timedelta; got {describe(duration)}",
            )
        if duration <= timedelta(0):
            raise ValueError(f"piezo duration must be greater than zero; got {duration!r}")

    @staticmethod
    def _as_timedelta(duration: int | float | timedelta) -> timedelta:
        """Turn a number of seconds into a timedelta; leave a timedelta as it is."""
        from j5aio._timedelta import timedelta

        if isinstance(duration, timedelta):
            return duration
        if isinstance(duration, bool) or not isinstance(duration, int | float):
            raise TypeError(
                f"piezo duration must be {_DURATION_ALLOWED}; got {describe(duration)}",
            )
        try:
            return timedelta(seconds=duration)
        except (OverflowError, ValueError):  # infinite, NaN, or too long
            raise ValueError(
                f"piezo duration must be {_DURATION_ALLOWED}; got {duration!r}, "
                "which is not a finite length of time a timedelta can hold",
            ) from None

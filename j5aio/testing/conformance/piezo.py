"""The conformance suite of :class:`~j5aio.components.piezo.PiezoInterface`."""

from __future__ import annotations

import math
from collections.abc import Awaitable, Callable, Sequence
from dataclasses import dataclass
from datetime import timedelta
from typing import ClassVar

import anyio

from j5aio.components.piezo import PiezoInterface

from ._base import InterfaceConformance, Subject, require

__all__ = ["PiezoInterfaceConformance", "PiezoSubject"]

#: A note as heard: (duration, pitch in hertz).
Heard = tuple[timedelta, float]


@dataclass(kw_only=True)
class PiezoSubject(Subject):
    """A backend implementing :class:`.PiezoInterface`, for :class:`PiezoInterfaceConformance`.

    :param observe: returns every note piezo ``identifier`` has been asked to play so far,
        oldest first, as (duration, pitch in hertz), read from a simulator (say).
    """

    backend: PiezoInterface
    observe: Callable[[int], Awaitable[Sequence[Heard]]] | None = None


class PiezoInterfaceConformance(InterfaceConformance[PiezoSubject]):
    """What every implementation of :class:`~j5aio.components.piezo.PiezoInterface` must do.

    * ``buzz`` returns once the note is accepted, well before it has finished playing;
    * the board plays the duration and pitch asked for (within its resolution);
    * an identifier the board does not have is refused, sending nothing.
    """

    #: How far a pitch heard may be from the pitch asked for, in hertz.
    pitch_tolerance: ClassVar[float] = 1.0

    #: How far a duration heard may be from the duration asked for.
    duration_tolerance: ClassVar[timedelta] = timedelta(milliseconds=1)

    #: The notes played by the tests: (duration, pitch in hertz).
    notes: ClassVar[tuple[Heard, ...]] = (
        (timedelta(milliseconds=100), 440.0),
        (timedelta(milliseconds=250), 1047.0),
        (timedelta(seconds=1), 2000.0),
    )

    async def test_buzz_returns_before_the_note_ends(self, subject: PiezoSubject) -> None:
        """A long note is accepted at once: buzz does not wait for it to finish."""
        long_note = timedelta(seconds=self.call_timeout * 2)
        allowed = long_note.total_seconds() / 2
        for identifier in subject.identifiers:
            with anyio.move_on_after(allowed) as scope:
                await subject.backend.buzz(identifier, long_note, 440.0)
            assert not scope.cancelled_caught, (
                f"buzz on piezo {identifier} took over {allowed:.1f} s for a "
                f"{long_note.total_seconds():.1f} s note: it must not wait for the note"
            )

    async def test_the_board_plays_what_was_asked(self, subject: PiezoSubject) -> None:
        """The duration and pitch asked for reach the board, in order."""
        observe = require(subject.observe, "observe")
        with self.bounded():
            for identifier in subject.identifiers:
                before = len(await observe(identifier))
                for duration, pitch in self.notes:
                    await subject.backend.buzz(identifier, duration, pitch)
                heard = list(await observe(identifier))[before:]
                assert len(heard) == len(self.notes), (
                    f"piezo {identifier} was asked for {len(self.notes)} notes but "
                    f"played {len(heard)}"
                )
                for (duration, pitch), (got_duration, got_pitch) in zip(
                    self.notes, heard, strict=True,
                ):
                    assert abs(got_duration - duration) <= self.duration_tolerance, (
                        f"asked for {duration}, the board played {got_duration}"
                    )
                    assert math.isclose(got_pitch, pitch, abs_tol=self.pitch_tolerance), (
                        f"asked for {pitch} Hz, the board played {got_pitch} Hz"
                    )

    async def test_out_of_range_identifier_raises(self, subject: PiezoSubject) -> None:
        """A piezo the board does not have is refused."""
        backend = subject.backend
        await self.assert_refused(
            subject, lambda i: backend.buzz(i, timedelta(milliseconds=100), 440.0), "buzz",
        )

"""The conformance suite of :class:`~j5aio.components.derived.ultrasound.UltrasoundInterface`."""

from __future__ import annotations

import math
from collections.abc import Awaitable, Callable, Sequence
from dataclasses import dataclass
from datetime import timedelta
from typing import ClassVar

from j5aio.components.derived.ultrasound import UltrasoundInterface

from ._base import InterfaceConformance, Subject, require

__all__ = ["SPEED_OF_SOUND", "UltrasoundInterfaceConformance", "UltrasoundSubject"]

#: The speed of sound in air at room temperature, in metres per second.
SPEED_OF_SOUND = 343.0


@dataclass(kw_only=True)
class UltrasoundSubject(Subject):
    """A backend implementing :class:`~j5aio.components.derived.ultrasound.UltrasoundInterface`.

    ``identifiers`` lists the pins the board has, for the bad-identifier test.

    :param pairs: the (trigger pin, echo pin) pairs to test a sensor on.
    :param place_object: puts an object ``metres`` away from the sensor on the pair
        (trigger, echo), or takes every object away (``None``: no echo), so that the next
        reading sees it. For a console backend: queue the answers to the prompts.
    """

    backend: UltrasoundInterface
    pairs: Sequence[tuple[int, int]] = ()
    place_object: Callable[[int, int, float | None], Awaitable[None]] | None = None


class UltrasoundInterfaceConformance(InterfaceConformance[UltrasoundSubject]):
    """What every implementation of :class:`.UltrasoundInterface` must do.

    * the distance read is the object's (within :attr:`distance_tolerance`), and the
      pulse read is the time sound takes there and back;
    * no echo reads as ``None``, for both;
    * a pin the board does not have is refused, as trigger and as echo.
    """

    #: How far a distance read may be from the object's, in metres.
    distance_tolerance: ClassVar[float] = 0.01

    #: The distances the tests place an object at, in metres.
    distances: ClassVar[tuple[float, ...]] = (0.1, 0.5, 1.75)

    async def test_readings_have_the_right_types(self, subject: UltrasoundSubject) -> None:
        """A pulse reads as a timedelta or None, a distance as a float or None."""
        with self.bounded():
            for trigger, echo in subject.pairs:
                if subject.place_object is not None:
                    await subject.place_object(trigger, echo, self.distances[0])
                pulse = await subject.backend.get_ultrasound_pulse(trigger, echo)
                assert pulse is None or isinstance(pulse, timedelta), f"pulse read {pulse!r}"
                if subject.place_object is not None:
                    await subject.place_object(trigger, echo, self.distances[0])
                distance = await subject.backend.get_ultrasound_distance(trigger, echo)
                assert distance is None or isinstance(distance, float), (
                    f"distance read {distance!r}"
                )

    async def test_readings_follow_the_object(self, subject: UltrasoundSubject) -> None:
        """The distance and the echo time match where the object is."""
        place_object = require(subject.place_object, "place_object")
        with self.bounded():
            for trigger, echo in subject.pairs:
                for metres in self.distances:
                    await place_object(trigger, echo, metres)
                    distance = await subject.backend.get_ultrasound_distance(trigger, echo)
                    assert distance is not None, f"no echo from an object {metres} m away"
                    assert math.isclose(distance, metres, abs_tol=self.distance_tolerance), (
                        f"object at {metres} m reads as {distance} m"
                    )
                    await place_object(trigger, echo, metres)
                    pulse = await subject.backend.get_ultrasound_pulse(trigger, echo)
                    assert pulse is not None, f"no echo from an object {metres} m away"
                    heard = pulse.total_seconds() * SPEED_OF_SOUND / 2
                    assert math.isclose(heard, metres, rel_tol=0.05, abs_tol=0.01), (
                        f"object at {metres} m gives a {pulse} echo, which is {heard:.3f} m"
                    )

    async def test_no_echo_reads_none(self, subject: UltrasoundSubject) -> None:
        """With nothing in front of the sensor, both readings are None."""
        place_object = require(subject.place_object, "place_object")
        with self.bounded():
            for trigger, echo in subject.pairs:
                await place_object(trigger, echo, None)
                distance = await subject.backend.get_ultrasound_distance(trigger, echo)
                assert distance is None, f"no object, but the distance reads {distance!r}"
                await place_object(trigger, echo, None)
                pulse = await subject.backend.get_ultrasound_pulse(trigger, echo)
                assert pulse is None, f"no object, but the pulse reads {pulse!r}"

    async def test_out_of_range_identifier_raises(self, subject: UltrasoundSubject) -> None:
        """A pin the board does not have is refused, as trigger or as echo."""
        backend = subject.backend
        trigger, echo = subject.pairs[0]
        await self.assert_refused(
            subject, lambda i: backend.get_ultrasound_pulse(i, echo), "get_ultrasound_pulse",
        )
        await self.assert_refused(
            subject, lambda i: backend.get_ultrasound_pulse(trigger, i), "get_ultrasound_pulse",
        )
        await self.assert_refused(
            subject,
            lambda i: backend.get_ultrasound_distance(i, echo),
            "get_ultrasound_distance",
        )
        await self.assert_refused(
            subject,
            lambda i: backend.get_ultrasound_distance(trigger, i),
            "get_ultrasound_distance",
        )

"""The conformance suite of :class:`~j5aio.components.distance_sensor.DistanceSensorInterface`.

It is written with the public base, :mod:`j5aio.testing.conformance.base`, only: a model
for the suite of an interface of your own.
"""

from __future__ import annotations

import math
from collections.abc import Awaitable, Callable
from dataclasses import dataclass
from typing import ClassVar

from j5aio.components.distance_sensor import DistanceSensorInterface
from j5aio.testing.conformance.base import InterfaceConformance, Subject, require

__all__ = ["DistanceSensorInterfaceConformance", "DistanceSensorSubject"]


@dataclass(kw_only=True)
class DistanceSensorSubject(Subject):
    """A backend implementing :class:`~j5aio.components.distance_sensor.DistanceSensorInterface`.

    :param place_object: puts an object ``millimetres`` away from sensor ``identifier``,
        or takes every object out of its range (``None``), so that its next reading sees
        it. For a console backend: queue the answer to the prompt.
    """

    backend: DistanceSensorInterface
    place_object: Callable[[int, float | None], Awaitable[None]] | None = None


class DistanceSensorInterfaceConformance(InterfaceConformance[DistanceSensorSubject]):
    """What every implementation of :class:`.DistanceSensorInterface` must do.

    * a reading is a finite number of millimetres, 0 or more (an ``int`` or a ``float``,
      never a ``bool``), or ``None``;
    * it is where the object is (within :attr:`tolerance_mm`), in millimetres: a backend
      that gives metres or centimetres fails;
    * with nothing in range the reading is ``None``, not 0 or a sentinel;
    * a sensor the board does not have is refused, sending nothing.
    """

    #: How far a reading may be from the object, in millimetres (1 for a board that
    #: reads whole millimetres, and rounds or truncates).
    tolerance_mm: ClassVar[float] = 1.0

    #: The distances the tests place an object at, in millimetres: within the range of
    #: every sensor of the board.
    distances_mm: ClassVar[tuple[float, ...]] = (40.0, 250.0, 1234.0)

    @staticmethod
    def check_reading(identifier: int, reading: object) -> None:
        """Fail unless ``reading`` is ``None`` or a finite number of millimetres, 0 or more."""
        if reading is None:
            return
        assert isinstance(reading, int | float) and not isinstance(reading, bool), (
            f"sensor {identifier} read {reading!r}: expected a number of millimetres or None"
        )
        assert math.isfinite(reading) and reading >= 0, (
            f"sensor {identifier} read {reading!r} mm: a distance is finite and 0 or more; "
            "no reading is None"
        )

    async def test_readings_have_the_right_types(self, subject: DistanceSensorSubject) -> None:
        """Every sensor reads as a finite number of millimetres, 0 or more, or None."""
        with self.bounded():
            for identifier in subject.identifiers:
                if subject.place_object is not None:
                    await subject.place_object(identifier, self.distances_mm[0])
                reading = await subject.backend.get_distance_sensor_mm(identifier)
                self.check_reading(identifier, reading)

    async def test_readings_follow_the_object(self, subject: DistanceSensorSubject) -> None:
        """Each sensor reads the object's distance, in millimetres."""
        place_object = require(subject.place_object, "place_object")
        with self.bounded():
            for identifier in subject.identifiers:
                for millimetres in self.distances_mm:
                    await place_object(identifier, millimetres)
                    reading = await subject.backend.get_distance_sensor_mm(identifier)
                    self.check_reading(identifier, reading)
                    assert reading is not None, (
                        f"sensor {identifier} has no reading of an object {millimetres} mm away"
                    )
                    assert abs(reading - millimetres) <= self.tolerance_mm, (
                        f"sensor {identifier}: an object {millimetres} mm away reads as "
                        f"{reading} mm (a wrong unit or scale?)"
                    )

    async def test_nothing_in_range_reads_none(self, subject: DistanceSensorSubject) -> None:
        """With nothing in range a sensor reads None, not 0 or another stand-in."""
        place_object = require(subject.place_object, "place_object")
        with self.bounded():
            for identifier in subject.identifiers:
                await place_object(identifier, None)
                reading = await subject.backend.get_distance_sensor_mm(identifier)
                assert reading is None, (
                    f"sensor {identifier} has nothing in range but reads {reading!r}; "
                    "no reading must be None"
                )

    async def test_out_of_range_identifier_raises(self, subject: DistanceSensorSubject) -> None:
        """A sensor the board does not have is refused, sending nothing."""
        await self.assert_refused(subject, subject.backend.get_distance_sensor_mm)

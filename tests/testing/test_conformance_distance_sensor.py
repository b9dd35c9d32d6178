"""The distance sensor's suite passes a correct backend and catches each kind of wrong one."""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import ClassVar

import anyio
import pytest

from j5aio.components.distance_sensor import DistanceSensorInterface
from j5aio.testing.conformance import (
    DistanceSensorInterfaceConformance,
    DistanceSensorSubject,
)
from j5aio.testing.conformance.base import HOOK_SKIP_MARK

SENSORS = range(3)


class TableSensors(DistanceSensorInterface):
    """Three sensors that read whole millimetres of where objects are; 2 m of range.

    Each reading "sends" a command, recorded in :attr:`sent`, as a board's backend would.
    """

    RANGE_MM: ClassVar[float] = 2000.0

    def __init__(self) -> None:
        self.objects: dict[int, float | None] = dict.fromkeys(SENSORS)
        self.sent = bytearray()

    def check(self, identifier: int) -> None:
        if identifier not in SENSORS:
            raise ValueError(f"the board has sensors 0 to 2, not {identifier}")

    def mm(self, identifier: int) -> float | None:
        where = self.objects[identifier]
        return None if where is None or where > self.RANGE_MM else float(round(where))

    async def get_distance_sensor_mm(self, identifier: int) -> float | None:
        self.check(identifier)
        self.sent += b"D%d\n" % identifier
        return self.mm(identifier)


def subject_of(backend: TableSensors, *, hooks: bool = True) -> DistanceSensorSubject:
    async def place_object(identifier: int, millimetres: float | None) -> None:
        backend.objects[identifier] = millimetres

    async def cleanup() -> None:
        return None

    return DistanceSensorSubject(
        backend=backend,
        identifiers=SENSORS,
        place_object=place_object if hooks else None,
        traffic=(lambda: bytes(backend.sent)) if hooks else None,
        cleanup=cleanup,
    )


class TestACorrectBackend(DistanceSensorInterfaceConformance):
    async def make_backend(self) -> DistanceSensorSubject:
        return subject_of(TableSensors())


# -- the suite against deliberately wrong backends ----------------------------------------


class InMetres(TableSensors):
    async def get_distance_sensor_mm(self, identifier: int) -> float | None:
        self.check(identifier)
        reading = self.mm(identifier)
        return None if reading is None else reading / 1000


class ZeroForNothing(TableSensors):
    async def get_distance_sensor_mm(self, identifier: int) -> float | None:
        self.check(identifier)
        return self.mm(identifier) or 0.0


class MinusOneForNothing(TableSensors):
    async def get_distance_sensor_mm(self, identifier: int) -> float | None:
        self.check(identifier)
        reading = self.mm(identifier)
        return -1.0 if reading is None else reading


class AcceptsAnySensor(TableSensors):
    async def get_distance_sensor_mm(self, identifier: int) -> float | None:
        if identifier not in SENSORS:
            return None
        return self.mm(identifier)


class SendsBeforeChecking(TableSensors):
    async def get_distance_sensor_mm(self, identifier: int) -> float | None:
        self.sent += b"D%d\n" % identifier
        self.check(identifier)
        return self.mm(identifier)


class SaysTrue(TableSensors):
    async def get_distance_sensor_mm(self, identifier: int) -> float | None:
        self.check(identifier)
        return True


class NeverAnswers(TableSensors):
    async def get_distance_sensor_mm(self, identifier: int) -> float | None:
        await anyio.sleep_forever()
        raise AssertionError("unreachable")


class QuickSuite(DistanceSensorInterfaceConformance):
    """The suite, run by hand on one backend; a hang counts after a tenth of a second."""

    call_timeout: ClassVar[float] = 0.1

    async def make_backend(self) -> DistanceSensorSubject:
        raise NotImplementedError  # the tests below hand the suite its subject


Check = Callable[[QuickSuite, DistanceSensorSubject], object]

WRONG = [
    (InMetres, QuickSuite.test_readings_follow_the_object, "a wrong unit or scale"),
    (ZeroForNothing, QuickSuite.test_nothing_in_range_reads_none, "no reading must be None"),
    (MinusOneForNothing, QuickSuite.test_nothing_in_range_reads_none, "reads -1.0"),
    (AcceptsAnySensor, QuickSuite.test_out_of_range_identifier_raises, "accepted bad identifier"),
    (SendsBeforeChecking, QuickSuite.test_out_of_range_identifier_raises, "sent bytes"),
    (SaysTrue, QuickSuite.test_readings_have_the_right_types, "expected a number"),
    (NeverAnswers, QuickSuite.test_readings_have_the_right_types, "did not finish"),
]


@pytest.mark.parametrize(("backend_class", "check", "says"), WRONG)
async def test_the_suite_catches_a_wrong_backend(
    backend_class: type[TableSensors], check: Check, says: str,
) -> None:
    suite = QuickSuite()
    with pytest.raises((AssertionError, pytest.fail.Exception), match=re.escape(says)):
        await check(suite, subject_of(backend_class()))  # type: ignore[misc]


@pytest.mark.parametrize(("backend_class", "check", "says"), WRONG)
async def test_the_same_check_passes_a_correct_backend(
    backend_class: type[TableSensors], check: Check, says: str,
) -> None:
    await check(QuickSuite(), subject_of(TableSensors()))  # type: ignore[misc]


async def test_a_sensor_beyond_its_range_is_caught_by_the_distances_it_is_given() -> None:
    class ShortRange(TableSensors):
        RANGE_MM = 1000.0

    with pytest.raises(AssertionError, match=re.escape("no reading of an object 1234.0 mm away")):
        await QuickSuite().test_readings_follow_the_object(subject_of(ShortRange()))

    class WithinAMetre(QuickSuite):
        distances_mm = (40.0, 250.0, 999.0)

    await WithinAMetre().test_readings_follow_the_object(subject_of(ShortRange()))


async def test_without_hooks_the_checks_that_need_them_skip_naming_them() -> None:
    subject = subject_of(TableSensors(), hooks=False)
    assert subject.missing_hooks() == ["traffic", "place_object"]
    suite = QuickSuite()
    with pytest.raises(pytest.skip.Exception, match=f"'place_object' {HOOK_SKIP_MARK}"):
        await suite.test_readings_follow_the_object(subject)
    with pytest.raises(pytest.skip.Exception, match="'traffic', 'place_object'"):
        await suite.test_every_hook_is_given(subject)
    await suite.test_readings_have_the_right_types(subject)  # needs no hook

"""The distance sensor: millimetres and metres from one reading, no reading as None."""

from __future__ import annotations

import pytest

from j5aio.components import (
    LED,
    DistanceSensor,
    DistanceSensorInterface,
    GPIOPin,
    GPIOPinMode,
    LEDInterface,
    Rangefinder,
    UltrasoundSensor,
)
from j5aio.errors import NotSupportedByComponentError

from .component_fakes import RecordingBackend


class Sensors(DistanceSensorInterface):
    """Answers each sensor's reading from a table, and records what it was asked."""

    def __init__(self, readings: dict[int, float | None]) -> None:
        self.readings = readings
        self.asked: list[int] = []

    async def get_distance_sensor_mm(self, identifier: int) -> float | None:
        self.asked.append(identifier)
        return self.readings[identifier]


async def test_one_reading_gives_millimetres_and_metres() -> None:
    backend = Sensors({0: 250.0, 1: 1234.5})
    first, second = DistanceSensor(0, backend), DistanceSensor(1, backend)

    assert await first.distance_mm() == 250.0
    assert await first.distance() == 0.25
    assert await second.distance_mm() == 1234.5
    assert await second.distance() == 1.2345
    assert backend.asked == [0, 0, 1, 1]  # one command for each reading, by its own number


async def test_no_reading_is_none_in_both_units() -> None:
    sensor = DistanceSensor(3, Sensors({3: None}))
    assert await sensor.distance_mm() is None
    assert await sensor.distance() is None


async def test_a_whole_number_of_millimetres_reads_as_a_float() -> None:
    sensor = DistanceSensor(0, Sensors({0: 87}))
    millimetres = await sensor.distance_mm()
    assert millimetres == 87.0 and type(millimetres) is float
    assert await sensor.distance() == 0.087


def test_the_sensor_is_numbered_and_names_its_interface() -> None:
    sensor = DistanceSensor(2, Sensors({}))
    assert sensor.identifier == 2
    assert DistanceSensor.interface_class() is DistanceSensorInterface
    assert repr(sensor) == "<DistanceSensor identifier=2>"
    with pytest.raises(AttributeError):
        sensor.distanse = 3  # type: ignore[attr-defined]  # __slots__: a typo is an error


def test_a_backend_without_the_interface_is_refused() -> None:
    class JustLEDs(LEDInterface):
        async def get_led_state(self, identifier: int) -> bool:
            return False

        async def set_led_state(self, identifier: int, state: bool) -> None:
            return None

    with pytest.raises(TypeError, match="DistanceSensor needs a backend that implements "
                       "DistanceSensorInterface, but JustLEDs does not"):
        DistanceSensor(0, JustLEDs())  # type: ignore[arg-type]
    assert LED(0, JustLEDs()).identifier == 0


def ultrasound(backend: RecordingBackend, *, distance_mode: bool = True) -> UltrasoundSensor:
    pins = [
        GPIOPin(
            identifier, backend,
            initial_mode=GPIOPinMode.DIGITAL_OUTPUT, firmware_modes={UltrasoundSensor},
        )
        for identifier in (4, 5)
    ]
    return UltrasoundSensor(pins[0], pins[1], backend, distance_mode=distance_mode)


async def test_an_ultrasound_sensor_is_a_rangefinder_read_in_both_units() -> None:
    backend = RecordingBackend()
    backend.distance = 0.123  # what a backend makes of 123 mm
    sensor = ultrasound(backend)

    assert isinstance(sensor, Rangefinder)
    assert await sensor.distance() == 0.123
    assert await sensor.distance_mm() == 123.0  # not 123.00000000000001
    assert backend.calls == [("get_ultrasound_distance", (4, 5))] * 2

    backend.distance = None
    assert await sensor.distance_mm() is None


async def test_an_ultrasound_sensor_without_distance_mode_refuses_millimetres_too() -> None:
    backend = RecordingBackend()
    sensor = ultrasound(backend, distance_mode=False)
    with pytest.raises(NotSupportedByComponentError, match="distance_mode=False"):
        await sensor.distance_mm()
    assert backend.calls == []


async def test_code_for_any_rangefinder_reads_both_kinds_alike() -> None:
    async def too_close(sensor: Rangefinder) -> bool:
        metres = await sensor.distance()
        return metres is not None and metres < 0.2

    backend = RecordingBackend()
    backend.distance = 0.15
    assert await too_close(ultrasound(backend))
    assert not await too_close(DistanceSensor(0, Sensors({0: 250})))
    assert not await too_close(DistanceSensor(0, Sensors({0: None})))


def test_a_rangefinder_must_say_how_it_measures() -> None:
    class Half(Rangefinder):
        identifier = 0

        @classmethod
        def interface_class(cls) -> type[DistanceSensorInterface]:
            return DistanceSensorInterface

    with pytest.raises(TypeError, match="distance_mm"):
        Half()  # type: ignore[abstract]

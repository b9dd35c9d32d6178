from datetime import timedelta

import pytest

from j5aio.components import (
    DerivedComponent,
    GPIOPin,
    GPIOPinMode,
    UltrasoundInterface,
    UltrasoundSensor,
)
from j5aio.errors import NotSupportedByComponentError

from .component_fakes import RecordingBackend


def make_pin(identifier: int, backend: RecordingBackend, *, ultrasound: bool = True) -> GPIOPin:
    return GPIOPin(
        identifier,
        backend,
        initial_mode=GPIOPinMode.DIGITAL_OUTPUT,
        firmware_modes={UltrasoundSensor} if ultrasound else set(),
    )


async def test_pulse_and_distance_ask_the_backend_with_both_pins() -> None:
    backend = RecordingBackend()
    sensor = UltrasoundSensor(make_pin(4, backend), make_pin(5, backend), backend)

    assert await sensor.pulse() == timedelta(milliseconds=3)
    assert await sensor.distance() == 0.5
    assert backend.calls == [
        ("get_ultrasound_pulse", (4, 5)),
        ("get_ultrasound_distance", (4, 5)),
    ]


async def test_no_echo_gives_none() -> None:
    backend = RecordingBackend()
    backend.echo = None
    backend.distance = None
    sensor = UltrasoundSensor(make_pin(4, backend), make_pin(5, backend), backend)
    assert await sensor.pulse() is None
    assert await sensor.distance() is None


async def test_distance_is_refused_when_distance_mode_is_off() -> None:
    backend = RecordingBackend()
    sensor = UltrasoundSensor(
        make_pin(4, backend), make_pin(5, backend), backend, distance_mode=False,
    )
    with pytest.raises(NotSupportedByComponentError, match=r"distance_mode=False.*use pulse"):
        await sensor.distance()
    assert backend.calls == []
    assert await sensor.pulse() == timedelta(milliseconds=3)


@pytest.mark.parametrize(
    ("trigger_ok", "echo_ok", "named"),
    [(False, True, "pin 4 does not"), (True, False, "pin 5 does not"),
     (False, False, "pins 4 and 5 do not")],
)
def test_pins_without_the_ultrasound_firmware_mode_are_refused(
    trigger_ok: bool, echo_ok: bool, named: str,
) -> None:
    backend = RecordingBackend()
    trigger = make_pin(4, backend, ultrasound=trigger_ok)
    echo = make_pin(5, backend, ultrasound=echo_ok)
    with pytest.raises(NotSupportedByComponentError) as info:
        UltrasoundSensor(trigger, echo, backend)
    assert str(info.value) == (
        f"UltrasoundSensor needs pins whose firmware modes include UltrasoundSensor, "
        f"but {named}; use pins that support an ultrasound sensor"
    )


def test_is_a_derived_component_without_an_identifier() -> None:
    backend = RecordingBackend()
    sensor = UltrasoundSensor(make_pin(4, backend), make_pin(5, backend), backend)
    assert isinstance(sensor, DerivedComponent)
    with pytest.raises(NotSupportedByComponentError):
        sensor.identifier  # noqa: B018
    assert repr(sensor) == "<UltrasoundSensor derived>"
    assert UltrasoundSensor.interface_class() is UltrasoundInterface

"""The conformance suite of the new interface, on j5aio's public suite base."""

from __future__ import annotations

import math
from collections.abc import Awaitable, Callable
from dataclasses import dataclass
from typing import ClassVar

from j5aio.testing.conformance.base import InterfaceConformance, Subject, require

from .light_sensor import LightSensor, LightSensorInterface

__all__ = ["LightSensorInterfaceConformance", "LightSensorSubject"]


@dataclass(kw_only=True)
class LightSensorSubject(Subject):
    """A backend implementing :class:`LightSensorInterface`, with its hooks.

    :param set_lux: makes ``lux`` fall on sensor ``identifier`` (feeds the board).
    :param observe_gain: returns the gain sensor ``identifier`` really has (observes the
        board).
    """

    backend: LightSensorInterface
    set_lux: Callable[[int, float], Awaitable[None]] | None = None
    observe_gain: Callable[[int], Awaitable[int]] | None = None


class LightSensorInterfaceConformance(InterfaceConformance[LightSensorSubject]):
    """What every implementation of :class:`LightSensorInterface` must do.

    * the light read is the light on the sensor (within :attr:`tolerance_lux`);
    * a gain set is the gain the board has, and the gain read back;
    * a sensor the board does not have is refused, sending nothing.
    """

    #: How far a reading may be from the light on the sensor, in lux.
    tolerance_lux: ClassVar[float] = 0.05

    #: The light the tests shine on each sensor, in lux.
    lights: ClassVar[tuple[float, ...]] = (0.0, 12.5, 480.0, 20_000.0)

    async def test_lux_follows_the_light(self, subject: LightSensorSubject) -> None:
        """Each sensor reads the light falling on it, in lux."""
        set_lux = require(subject.set_lux, "set_lux")
        with self.bounded():
            for identifier in subject.identifiers:
                for lux in self.lights:
                    await set_lux(identifier, lux)
                    got = await subject.backend.get_light_sensor_lux(identifier)
                    assert isinstance(got, float) and math.isfinite(got), (
                        f"sensor {identifier} read {got!r}, not a finite float"
                    )
                    assert abs(got - lux) <= self.tolerance_lux, (
                        f"sensor {identifier} has {lux} lux on it but reads {got}"
                    )

    async def test_a_gain_set_is_the_boards_and_reads_back(
        self, subject: LightSensorSubject,
    ) -> None:
        """Every gain set is the gain the board has, and the one read back."""
        with self.bounded():
            for identifier in subject.identifiers:
                for gain in (*LightSensor.GAINS, LightSensor.GAINS[0]):
                    await subject.backend.set_light_sensor_gain(identifier, gain)
                    if subject.observe_gain is not None:
                        seen = await subject.observe_gain(identifier)
                        assert seen == gain, f"gain {gain} was set, the board has {seen}"
                    got = await subject.backend.get_light_sensor_gain(identifier)
                    assert got == gain, f"gain {gain} was set, but {got!r} reads back"

    async def test_out_of_range_identifier_raises(self, subject: LightSensorSubject) -> None:
        """A sensor the board does not have is refused, sending nothing."""
        backend = subject.backend
        await self.assert_refused(subject, backend.get_light_sensor_lux, "get_light_sensor_lux")
        await self.assert_refused(
            subject, backend.get_light_sensor_gain, "get_light_sensor_gain",
        )
        await self.assert_refused(
            subject, lambda i: backend.set_light_sensor_gain(i, 4), "set_light_sensor_gain",
        )

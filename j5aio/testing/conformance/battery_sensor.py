"""The conformance suite of :class:`~j5aio.components.battery_sensor.BatterySensorInterface`."""

from __future__ import annotations

import math
from collections.abc import Awaitable, Callable
from dataclasses import dataclass
from typing import ClassVar

from j5aio.components.battery_sensor import BatterySensorInterface

from ._base import InterfaceConformance, Subject, require

__all__ = ["BatterySensorInterfaceConformance", "BatterySensorSubject"]


@dataclass(kw_only=True)
class BatterySensorSubject(Subject):
    """A backend implementing :class:`~j5aio.components.battery_sensor.BatterySensorInterface`.

    :param set_reading: makes sensor ``identifier`` measure ``volts`` and ``amps``, so
        that the next readings see them. For a console backend: queue the answers.
    """

    backend: BatterySensorInterface
    set_reading: Callable[[int, float, float], Awaitable[None]] | None = None


class BatterySensorInterfaceConformance(InterfaceConformance[BatterySensorSubject]):
    """What every implementation of :class:`.BatterySensorInterface` must do.

    * voltage and current are finite floats;
    * they follow the battery (within :attr:`voltage_tolerance` and
      :attr:`current_tolerance`);
    * an identifier the board does not have is refused, sending nothing.
    """

    #: How far a voltage read may be from the battery's, in volts.
    voltage_tolerance: ClassVar[float] = 0.01

    #: How far a current read may be from the battery's, in amps.
    current_tolerance: ClassVar[float] = 0.01

    #: The (volts, amps) readings the tests make the battery give.
    readings: ClassVar[tuple[tuple[float, float], ...]] = (
        (12.0, 1.5), (11.1, 0.0), (12.6, 7.25),
    )

    async def test_readings_are_floats(self, subject: BatterySensorSubject) -> None:
        """Voltage and current read as finite floats."""
        with self.bounded():
            for identifier in subject.identifiers:
                if subject.set_reading is not None:
                    await subject.set_reading(identifier, *self.readings[0])
                for reading in (
                    await subject.backend.get_battery_sensor_voltage(identifier),
                    await subject.backend.get_battery_sensor_current(identifier),
                ):
                    assert isinstance(reading, float), f"read {reading!r}, not a float"
                    assert math.isfinite(reading), f"read {reading!r}, not a finite number"

    async def test_readings_follow_the_battery(self, subject: BatterySensorSubject) -> None:
        """The voltage and current read are those of the battery."""
        set_reading = require(subject.set_reading, "set_reading")
        with self.bounded():
            for identifier in subject.identifiers:
                for volts, amps in self.readings:
                    await set_reading(identifier, volts, amps)
                    got_volts = await subject.backend.get_battery_sensor_voltage(identifier)
                    got_amps = await subject.backend.get_battery_sensor_current(identifier)
                    assert math.isclose(got_volts, volts, abs_tol=self.voltage_tolerance), (
                        f"battery {identifier} is at {volts} V but reads {got_volts} V"
                    )
                    assert math.isclose(got_amps, amps, abs_tol=self.current_tolerance), (
                        f"battery {identifier} gives {amps} A but reads {got_amps} A"
                    )

    async def test_out_of_range_identifier_raises(self, subject: BatterySensorSubject) -> None:
        """A sensor the board does not have is refused."""
        backend = subject.backend
        await self.assert_refused(subject, backend.get_battery_sensor_voltage)
        await self.assert_refused(subject, backend.get_battery_sensor_current)

"""The conformance suite of :class:`~j5aio.components.supply_sensor.SupplySensorInterface`."""

from __future__ import annotations

import math
from collections.abc import Awaitable, Callable
from dataclasses import dataclass
from typing import ClassVar

from j5aio.components.supply_sensor import SupplySensorInterface

from ._base import InterfaceConformance, Subject, require

__all__ = ["SupplySensorInterfaceConformance", "SupplySensorSubject"]


@dataclass(kw_only=True)
class SupplySensorSubject(Subject):
    """A backend implementing :class:`~j5aio.components.supply_sensor.SupplySensorInterface`.

    :param set_reading: makes supply ``identifier`` measure ``volts`` and ``amps``.
    """

    backend: SupplySensorInterface
    set_reading: Callable[[int, float, float], Awaitable[None]] | None = None


class SupplySensorInterfaceConformance(InterfaceConformance[SupplySensorSubject]):
    """What every implementation of :class:`.SupplySensorInterface` must do.

    * voltage and current are finite floats that follow the rail (within
      :attr:`tolerance`);
    * an identifier the board does not have is refused, sending nothing.
    """

    #: How far a reading may be from the rail's, in volts or amps.
    tolerance: ClassVar[float] = 0.01

    #: The (volts, amps) readings the tests make the rail give.
    readings: ClassVar[tuple[tuple[float, float], ...]] = ((5.5, 0.0), (5.0, 2.25), (0.0, 0.0))

    async def test_readings_follow_the_supply(self, subject: SupplySensorSubject) -> None:
        """The voltage and current read are finite floats, those of the rail."""
        set_reading = require(subject.set_reading, "set_reading")
        with self.bounded():
            for identifier in subject.identifiers:
                for volts, amps in self.readings:
                    await set_reading(identifier, volts, amps)
                    got_volts = await subject.backend.get_supply_voltage(identifier)
                    got_amps = await subject.backend.get_supply_current(identifier)
                    for got in (got_volts, got_amps):
                        assert isinstance(got, float) and math.isfinite(got), (
                            f"supply {identifier} read {got!r}, not a finite float"
                        )
                    assert math.isclose(got_volts, volts, abs_tol=self.tolerance), (
                        f"supply {identifier} is at {volts} V but reads {got_volts} V"
                    )
                    assert math.isclose(got_amps, amps, abs_tol=self.tolerance), (
                        f"supply {identifier} gives {amps} A but reads {got_amps} A"
                    )

    async def test_out_of_range_identifier_raises(self, subject: SupplySensorSubject) -> None:
        """A supply the board does not have is refused."""
        backend = subject.backend
        await self.assert_refused(subject, backend.get_supply_voltage)
        await self.assert_refused(subject, backend.get_supply_current)

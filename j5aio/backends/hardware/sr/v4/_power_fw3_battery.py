"""The battery reading of the SR v4 power board (firmware 3), made on a program's first read.

Its public home is :mod:`~j5aio.backends.hardware.sr.v4.power_fw3_codec`, which imports
this module the first time the name is used there (or a reading is parsed): a start
reads no battery, so it does not pay for making the dataclass. The class says that home
as its module, so that its name, its documentation and the annotations that name it all
point there.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["BatteryReading"]


@dataclass(frozen=True)
class BatteryReading:
    """What the battery sensor reports."""

    __module__ = "j5aio.backends.hardware.sr.v4.power_fw3_codec"

    current_ma: int
    voltage_mv: int

    @property
    def current(self) -> float:
        """The battery current in amperes."""
        return self.current_ma / 1000

    @property
    def voltage(self) -> float:
        """The battery voltage in volts."""
        return self.voltage_mv / 1000

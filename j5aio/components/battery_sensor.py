"""Battery sensors: the voltage and current of the robot's battery."""

from __future__ import annotations

from abc import abstractmethod

from j5aio.components.component import Interface

__all__ = ["BatterySensorInterface"]


class BatterySensorInterface(Interface):
    """The coroutines a backend implements to read battery sensors."""

    @abstractmethod
    async def get_battery_sensor_voltage(self, identifier: int) -> float:
        """Return the battery voltage, in volts."""
        raise NotImplementedError

    @abstractmethod
    async def get_battery_sensor_current(self, identifier: int) -> float:
        """Return the current drawn from the battery, in amps."""
        raise NotImplementedError

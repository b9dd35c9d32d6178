"""Battery sensors: the voltage and current of the robot's battery."""

from __future__ import annotations

from abc import abstractmethod

from j5aio.components.component import Interface
from j5aio.components.identified import IdentifiedComponent

__all__ = ["BatterySensor", "BatterySensorInterface"]


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


class BatterySensor(IdentifiedComponent[BatterySensorInterface]):
    """A sensor that measures the robot's battery: its voltage and the current drawn.

    :param identifier: the number of the sensor on its board.
    :param backend: the backend that reads the sensor.
    """

    __slots__ = ()

    @classmethod
    def interface_class(cls) -> type[BatterySensorInterface]:
        """The interface a backend implements for battery sensors: :class:`BatterySensorInterface`."""  # noqa: E501
        return BatterySensorInterface

    async def get_voltage(self) -> float:
        """Return the battery's voltage, in volts.

        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        return await self._backend.get_battery_sensor_voltage(self._identifier)

    async def get_current(self) -> float:
        """Return the current drawn from the battery, in amps.

        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        return await self._backend.get_battery_sensor_current(self._identifier)

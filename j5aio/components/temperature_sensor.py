"""Temperature sensors: a board's own thermometer."""

from __future__ import annotations

from abc import abstractmethod

from j5aio.components.component import Interface
from j5aio.components.identified import IdentifiedComponent

__all__ = ["TemperatureSensor", "TemperatureSensorInterface"]


class TemperatureSensorInterface(Interface):
    """The coroutines a backend implements to read temperature sensors."""

    @abstractmethod
    async def get_temperature(self, identifier: int) -> float:
        """Return the temperature of sensor ``identifier``, in degrees Celsius."""
        raise NotImplementedError


class TemperatureSensor(IdentifiedComponent[TemperatureSensorInterface]):
    """A thermometer on a board, such as the power board's.

    :param identifier: the number of the sensor on its board.
    :param backend: the backend that reads the sensor.
    """

    __slots__ = ()

    @classmethod
    def interface_class(cls) -> type[TemperatureSensorInterface]:
        """The interface a backend implements: :class:`TemperatureSensorInterface`."""
        return TemperatureSensorInterface

    async def get_temperature(self) -> float:
        """Return the temperature, in degrees Celsius.

        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        return await self._backend.get_temperature(self._identifier)

"""Voltage sensors: a board's measure of one of its supply voltages."""

from __future__ import annotations

from abc import abstractmethod

from j5aio.components.component import Interface
from j5aio.components.identified import IdentifiedComponent

__all__ = ["VoltageSensor", "VoltageSensorInterface"]


class VoltageSensorInterface(Interface):
    """The coroutines a backend implements to read voltage sensors."""

    @abstractmethod
    async def get_voltage_sensor_voltage(self, identifier: int) -> float:
        """Return the voltage sensor ``identifier`` measures, in volts."""
        raise NotImplementedError


class VoltageSensor(IdentifiedComponent[VoltageSensorInterface]):
    """A voltmeter on a board: a regulator's output, or the board's input supply.

    :param identifier: the number of the sensor on its board.
    :param backend: the backend that reads the sensor.
    """

    __slots__ = ()

    @classmethod
    def interface_class(cls) -> type[VoltageSensorInterface]:
        """The interface a backend implements: :class:`VoltageSensorInterface`."""
        return VoltageSensorInterface

    async def get_voltage(self) -> float:
        """Return the voltage, in volts.

        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        return await self._backend.get_voltage_sensor_voltage(self._identifier)

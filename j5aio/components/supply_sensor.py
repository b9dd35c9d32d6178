"""Supply sensors: the voltage and current of a power rail on a board."""

from __future__ import annotations

from abc import abstractmethod

from j5aio.components.component import Interface
from j5aio.components.identified import IdentifiedComponent

__all__ = ["SupplySensor", "SupplySensorInterface"]


class SupplySensorInterface(Interface):
    """The coroutines a backend implements to read supply sensors."""

    @abstractmethod
    async def get_supply_voltage(self, identifier: int) -> float:
        """Return the voltage of supply ``identifier``, in volts."""
        raise NotImplementedError

    @abstractmethod
    async def get_supply_current(self, identifier: int) -> float:
        """Return the current drawn from supply ``identifier``, in amps."""
        raise NotImplementedError


class SupplySensor(IdentifiedComponent[SupplySensorInterface]):
    """A meter on one of a board's power rails (such as a servo board's servo supply).

    :param identifier: the number of the rail on its board.
    :param backend: the backend that reads the meter.
    """

    __slots__ = ()

    @classmethod
    def interface_class(cls) -> type[SupplySensorInterface]:
        """The interface a backend implements for supply sensors: :class:`SupplySensorInterface`."""
        return SupplySensorInterface

    async def get_voltage(self) -> float:
        """Return the rail's voltage, in volts.

        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        return await self._backend.get_supply_voltage(self._identifier)

    async def get_current(self) -> float:
        """Return the current drawn from the rail, in amps.

        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        return await self._backend.get_supply_current(self._identifier)

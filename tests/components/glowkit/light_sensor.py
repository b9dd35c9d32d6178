"""A new kind of component: a light sensor, with its interface."""

from __future__ import annotations

from abc import abstractmethod
from typing import ClassVar

from j5aio.components import IdentifiedComponent, Interface

__all__ = ["LightSensor", "LightSensorInterface"]


class LightSensorInterface(Interface):
    """The coroutines a backend implements to drive light sensors."""

    @abstractmethod
    async def get_light_sensor_lux(self, identifier: int) -> float:
        """Return the light on sensor ``identifier``, in lux."""
        raise NotImplementedError

    @abstractmethod
    async def get_light_sensor_gain(self, identifier: int) -> int:
        """Return the gain of sensor ``identifier``."""
        raise NotImplementedError

    @abstractmethod
    async def set_light_sensor_gain(self, identifier: int, gain: int) -> None:
        """Set the gain of sensor ``identifier``: one of :attr:`LightSensor.GAINS`."""
        raise NotImplementedError


class LightSensor(IdentifiedComponent[LightSensorInterface]):
    """A light sensor, read in lux, with a gain for dim light.

    :param identifier: the number of the sensor on its board.
    :param backend: the backend that drives the sensor.
    """

    __slots__ = ()

    #: The gains a light sensor can be set to.
    GAINS: ClassVar[tuple[int, ...]] = (1, 4, 16, 64)

    @classmethod
    def interface_class(cls) -> type[LightSensorInterface]:
        """The interface a backend implements: :class:`LightSensorInterface`."""
        return LightSensorInterface

    async def get_lux(self) -> float:
        """Return the light falling on the sensor, in lux."""
        return await self._backend.get_light_sensor_lux(self._identifier)

    async def get_gain(self) -> int:
        """Return the sensor's gain."""
        return await self._backend.get_light_sensor_gain(self._identifier)

    async def set_gain(self, gain: int) -> None:
        """Set the sensor's gain: a higher gain reads dimmer light.

        :raises TypeError: ``gain`` is not a whole number.
        :raises ValueError: ``gain`` is not one of :attr:`GAINS`.
        """
        if isinstance(gain, bool) or not isinstance(gain, int):
            raise TypeError(f"a gain must be an int, one of {self.GAINS}; got {gain!r}")
        if gain not in self.GAINS:
            raise ValueError(f"a gain must be one of {self.GAINS}; got {gain}")
        await self._backend.set_light_sensor_gain(self._identifier, gain)

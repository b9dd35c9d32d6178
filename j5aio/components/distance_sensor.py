"""Distance sensors: how far away the nearest object is.

:class:`Rangefinder` is anything that measures that distance, whatever it is made of;
:class:`DistanceSensor` is the common kind, a sensor a board numbers and reads with one
command (a time-of-flight or infrared sensor on a board of its own, say). The ultrasound
sensor on two Arduino pins,
:class:`~j5aio.components.derived.ultrasound.UltrasoundSensor`, is a :class:`Rangefinder`
too, so code written for one works with the other::

    async def too_close(sensor: Rangefinder) -> bool:
        metres = await sensor.distance()
        return metres is not None and metres < 0.2

Both give the distance in metres (:meth:`Rangefinder.distance`) and in millimetres
(:meth:`Rangefinder.distance_mm`), and ``None`` when the sensor has no reading (nothing in
range, or no echo).
"""

from __future__ import annotations

from abc import abstractmethod

from j5aio.components.component import Component, Interface
from j5aio.components.identified import IdentifiedComponent

__all__ = ["DistanceSensor", "DistanceSensorInterface", "Rangefinder"]


class Rangefinder(Component):
    """Anything that measures how far away the nearest object is.

    A subclass implements :meth:`distance_mm`; :meth:`distance` gives the same reading in
    metres. Neither takes an argument, so a program can take any rangefinder, whatever its
    board, and read it the same way.
    """

    __slots__ = ()

    @abstractmethod
    async def distance_mm(self) -> float | None:
        """Measure the distance to the nearest object, in millimetres.

        :returns: the distance, or ``None`` when there is no reading (nothing in range).
        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        raise NotImplementedError

    async def distance(self) -> float | None:
        """Measure the distance to the nearest object, in metres.

        :returns: the distance, or ``None`` when there is no reading (nothing in range).
        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        millimetres = await self.distance_mm()
        return None if millimetres is None else millimetres / 1000


class DistanceSensorInterface(Interface):
    """The coroutine a backend implements to read distance sensors."""

    @abstractmethod
    async def get_distance_sensor_mm(self, identifier: int) -> float | None:
        """Return the distance sensor ``identifier`` reads, in millimetres.

        :returns: the distance (0 or more, finite), or ``None`` when the sensor has no
            reading (nothing in range).
        :raises ValueError: the board has no sensor ``identifier``; nothing is sent.
        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        raise NotImplementedError


class DistanceSensor(IdentifiedComponent[DistanceSensorInterface], Rangefinder):
    """A distance sensor that a board numbers and reads with one command.

    A board lists them as ``distance_sensors``; each reads in millimetres
    (:meth:`distance_mm`) and in metres (:meth:`~Rangefinder.distance`), ``None`` when
    nothing is in range.

    :param identifier: the number of the sensor on its board.
    :param backend: the backend that reads the sensor.
    """

    __slots__ = ()

    @classmethod
    def interface_class(cls) -> type[DistanceSensorInterface]:
        """The interface a backend implements: :class:`DistanceSensorInterface`."""
        return DistanceSensorInterface

    async def distance_mm(self) -> float | None:
        """Measure the distance to the nearest object, in millimetres.

        :returns: the distance, or ``None`` when nothing is in range.
        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        millimetres = await self._backend.get_distance_sensor_mm(self._identifier)
        return None if millimetres is None else float(millimetres)

"""Ultrasound distance sensors, driven on a trigger pin and an echo pin."""

from __future__ import annotations

from abc import abstractmethod
from typing import TYPE_CHECKING

from j5aio.components.component import DerivedComponent, Interface
from j5aio.components.distance_sensor import Rangefinder
from j5aio.components.gpio_pin import GPIOPin
from j5aio.components.identified import checked_backend
from j5aio.errors import NotSupportedByComponentError

if TYPE_CHECKING:
    from j5aio._timedelta import timedelta
    from j5aio.backends.backend import Backend

__all__ = ["UltrasoundInterface", "UltrasoundSensor"]


class UltrasoundInterface(Interface):
    """The coroutines a backend implements to read ultrasound sensors."""

    @abstractmethod
    async def get_ultrasound_pulse(
        self,
        trigger_pin_identifier: int,
        echo_pin_identifier: int,
    ) -> timedelta | None:
        """Return how long the echo took, or ``None`` if no echo came back."""
        raise NotImplementedError

    @abstractmethod
    async def get_ultrasound_distance(
        self,
        trigger_pin_identifier: int,
        echo_pin_identifier: int,
    ) -> float | None:
        """Return the distance to the nearest object in metres, or ``None`` if no echo."""
        raise NotImplementedError


class UltrasoundSensor(DerivedComponent, Rangefinder):
    """An ultrasound distance sensor, such as an HC-SR04, wired to two GPIO pins.

    The sensor sends a burst of sound when its trigger pin is pulsed and raises its echo
    pin until the sound's echo comes back; the time taken gives the distance to the
    nearest object. It is a :class:`~j5aio.components.distance_sensor.Rangefinder`, read
    like every distance sensor: :meth:`distance` in metres, :meth:`distance_mm` in
    millimetres.

    :param gpio_trigger: the pin wired to the sensor's trigger.
    :param gpio_echo: the pin wired to the sensor's echo.
    :param backend: the backend that times the echo.
    :param distance_mode: allow :meth:`distance`; with ``False`` only :meth:`pulse`
        may be used.
    :raises NotSupportedByComponentError: a pin does not list ``UltrasoundSensor``
        among its firmware modes.
    """

    __slots__ = ("_backend", "_distance_mode", "_gpio_echo", "_gpio_trigger")

    def __init__(
        self,
        gpio_trigger: GPIOPin,
        gpio_echo: GPIOPin,
        backend: UltrasoundInterface | Backend,
        *,
        distance_mode: bool = True,
    ) -> None:
        unsupported = [
            str(pin.identifier)
            for pin in (gpio_trigger, gpio_echo)
            if not any(issubclass(type(self), mode) for mode in pin.firmware_modes)
        ]
        if unsupported:
            which = (
                f"pin {unsupported[0]} does not"
                if len(unsupported) == 1
                else f"pins {' and '.join(unsupported)} do not"
            )
            raise NotSupportedByComponentError(
                f"{type(self).__name__} needs pins whose firmware modes include "
                f"{type(self).__name__}, but {which}; use pins that support an "
                "ultrasound sensor",
            )
        self._gpio_trigger = gpio_trigger
        self._gpio_echo = gpio_echo
        self._backend: UltrasoundInterface = checked_backend(type(self), backend)
        self._distance_mode = distance_mode

    @classmethod
    def interface_class(cls) -> type[UltrasoundInterface]:
        """The interface a backend implements for these sensors: :class:`UltrasoundInterface`."""
        return UltrasoundInterface

    async def pulse(self) -> timedelta | None:
        """Send a pulse and return how long its echo took, or ``None`` if none came back.

        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        return await self._backend.get_ultrasound_pulse(
            self._gpio_trigger.identifier,
            self._gpio_echo.identifier,
        )

    async def distance(self) -> float | None:
        """Send a pulse and return the distance to the nearest object, in metres.

        Returns ``None`` if no echo came back (nothing in range).

        :raises NotSupportedByComponentError: the sensor was made with
            ``distance_mode=False``; use :meth:`pulse` instead.
        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        if not self._distance_mode:
            raise NotSupportedByComponentError(
                "this ultrasound sensor was made with distance_mode=False, so it cannot "
                "measure a distance; use pulse() to get the echo time instead",
            )
        return await self._backend.get_ultrasound_distance(
            self._gpio_trigger.identifier,
            self._gpio_echo.identifier,
        )

    async def distance_mm(self) -> float | None:
        """Send a pulse and return the distance to the nearest object, in millimetres.

        The same reading as :meth:`distance`, a thousand times larger; ``None`` if no
        echo came back (nothing in range).

        :raises NotSupportedByComponentError: the sensor was made with
            ``distance_mode=False``; use :meth:`pulse` instead.
        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        metres = await self.distance()
        # Rounded to a nanometre: undoes the float error of the backend's division by 1000.
        return None if metres is None else round(metres * 1000, 6)

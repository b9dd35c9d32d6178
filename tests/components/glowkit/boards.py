"""The Glow Board as students see it: four light sensors and a distance sensor."""

from __future__ import annotations

from typing import TYPE_CHECKING, ClassVar

from j5aio.boards.board import Board
from j5aio.components import DistanceSensor
from j5aio.numbered import NumberedComponents

from .light_sensor import LightSensor

if TYPE_CHECKING:
    from j5aio.backends.backend import Backend
    from j5aio.components import Component

__all__ = ["GlowBoard"]


class GlowBoard(Board):
    """The Glow Board: light sensors 0 to 3 and distance sensor 0.

    :param serial_number: the board's serial number.
    :param backend: the backend that drives it.
    """

    name: ClassVar[str] = "Glow Board"

    #: How many light sensors the board has.
    LIGHT_SENSOR_COUNT: ClassVar[int] = 4

    def __init__(self, serial_number: str, backend: Backend) -> None:
        super().__init__(serial_number, backend)
        self._light_sensors = NumberedComponents(
            (LightSensor(i, backend) for i in range(self.LIGHT_SENSOR_COUNT)),
            owner=self, kind="light sensor",
        )
        self._distance_sensors = NumberedComponents(
            [DistanceSensor(0, backend)], owner=self, kind="distance sensor",
        )

    @property
    def light_sensors(self) -> NumberedComponents[LightSensor]:
        """The light sensors, numbered 0 to 3."""
        return self._light_sensors

    @property
    def distance_sensors(self) -> NumberedComponents[DistanceSensor]:
        """The distance sensor, number 0."""
        return self._distance_sensors

    @staticmethod
    def supported_components() -> set[type[Component]]:
        """The components of the board: a backend must implement their interfaces."""
        return {LightSensor, DistanceSensor}

    async def make_safe(self) -> None:
        """Nothing to do: sensors are safe as they are."""

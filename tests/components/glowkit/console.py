"""The Glow Board on the console: asks the user for the readings, prints the settings."""

from __future__ import annotations

import math

from j5aio.backends.console.backend import ConsoleBackend
from j5aio.backends.console.console import Console
from j5aio.components import DistanceSensorInterface

from .boards import GlowBoard
from .light_sensor import LightSensorInterface

__all__ = ["GlowConsoleBackend"]

#: The answer that says the distance sensor sees nothing in range.
NOTHING = "-"


def millimetres(answer: str) -> float | None:
    """Turn the user's answer into a reading: ``-`` is no reading.

    :raises ValueError: not ``-`` nor a finite number, 0 or more (the console asks again).
    """
    if answer.strip() == NOTHING:
        return None
    number = float(answer)
    if not math.isfinite(number) or number < 0:
        raise ValueError(answer)
    return number


class GlowConsoleBackend(LightSensorInterface, DistanceSensorInterface, ConsoleBackend):
    """Stands in for a Glow Board with no board at all (``J5AIO_ENV=console``).

    :param serial: the board's serial number.
    :param console_class: the console to talk through (a test passes a scripted one).
    """

    board = GlowBoard

    def __init__(self, serial: str, console_class: type[Console] | None = None) -> None:
        super().__init__(serial, console_class)
        self._gains = [1] * GlowBoard.LIGHT_SENSOR_COUNT

    async def get_light_sensor_lux(self, identifier: int) -> float:
        """Ask the user for the light on a sensor."""
        self._check_identifier("light sensor", identifier, range(GlowBoard.LIGHT_SENSOR_COUNT))
        return await self.console.read(f"Light on light sensor {identifier} [lux]", float)

    async def get_light_sensor_gain(self, identifier: int) -> int:
        """Return the gain last set."""
        self._check_identifier("light sensor", identifier, range(GlowBoard.LIGHT_SENSOR_COUNT))
        return self._gains[identifier]

    async def set_light_sensor_gain(self, identifier: int, gain: int) -> None:
        """Print the new gain."""
        self._check_identifier("light sensor", identifier, range(GlowBoard.LIGHT_SENSOR_COUNT))
        self._gains[identifier] = gain
        await self.console.info(f"Light sensor {identifier} gain set to {gain}")

    async def get_distance_sensor_mm(self, identifier: int) -> float | None:
        """Ask the user how far away the nearest object is."""
        self._check_identifier("distance sensor", identifier, range(1))
        return await self.console.read(
            f"Distance for distance sensor {identifier} [mm, or {NOTHING} for nothing in range]",
            millimetres,
        )

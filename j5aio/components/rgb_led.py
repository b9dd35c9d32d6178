"""RGB LEDs: an LED with red, green and blue channels, each a duty cycle in [0, 1]."""

from __future__ import annotations

from abc import abstractmethod
from enum import IntEnum

from j5aio.components.component import Interface

__all__ = ["RGBChannel", "RGBColour", "RGBLEDInterface"]


class RGBChannel(IntEnum):
    """The three channels of an RGB LED."""

    RED = 0
    GREEN = 1
    BLUE = 2


RGBColour = tuple[float, float, float]
"""A colour: the (red, green, blue) duty cycles, each in [0, 1]."""


class RGBLEDInterface(Interface):
    """The coroutines a backend implements to drive RGB LEDs."""

    @abstractmethod
    async def get_rgb_led_channel_duty_cycle(
        self, identifier: int, channel: RGBChannel,
    ) -> float:
        """Return the duty cycle of ``channel`` of RGB LED ``identifier``."""
        raise NotImplementedError

    @abstractmethod
    async def set_rgb_led_channel_duty_cycle(
        self, identifier: int, channel: RGBChannel, duty_cycle: float,
    ) -> None:
        """Set the duty cycle of ``channel`` of RGB LED ``identifier``."""
        raise NotImplementedError

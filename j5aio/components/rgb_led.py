"""RGB LEDs: an LED with red, green and blue channels, each a duty cycle in [0, 1]."""

from __future__ import annotations

from abc import abstractmethod
from enum import IntEnum

from j5aio.components._checks import check_number, describe
from j5aio.components.component import Interface
from j5aio.components.identified import IdentifiedComponent

__all__ = ["RGBLED", "RGBChannel", "RGBColour", "RGBLEDInterface"]


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


_DUTY_ALLOWED = "a float between 0 (off) and 1 (full brightness)"


class RGBLED(IdentifiedComponent[RGBLEDInterface]):
    """An LED that mixes red, green and blue light into any colour.

    Each channel has a brightness (a duty cycle) between 0 (off) and 1 (full). Set one
    channel with ``await led.set_red(0.5)``, or all three at once with
    ``await led.set_colour((1, 0.5, 0))``.

    :param identifier: the number of the RGB LED on its board.
    :param backend: the backend that drives the LED.
    """

    __slots__ = ()

    @classmethod
    def interface_class(cls) -> type[RGBLEDInterface]:
        """The interface a backend implements to drive RGB LEDs: :class:`RGBLEDInterface`."""
        return RGBLEDInterface

    async def get_red(self) -> float:
        """Return the brightness of the red channel, between 0 and 1.

        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        return await self._get_channel(RGBChannel.RED)

    async def set_red(self, duty_cycle: float) -> None:
        """Set the brightness of the red channel.

        :raises TypeError: ``duty_cycle`` is not a number (or is a bool).
        :raises ValueError: ``duty_cycle`` is outside [0, 1], or NaN.
        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        await self._set_channel(RGBChannel.RED, duty_cycle)

    async def get_green(self) -> float:
        """Return the brightness of the green channel, between 0 and 1.

        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        return await self._get_channel(RGBChannel.GREEN)

    async def set_green(self, duty_cycle: float) -> None:
        """Set the brightness of the green channel.

        :raises TypeError: ``duty_cycle`` is not a number (or is a bool).
        :raises ValueError: ``duty_cycle`` is outside [0, 1], or NaN.
        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        await self._set_channel(RGBChannel.GREEN, duty_cycle)

    async def get_blue(self) -> float:
        """Return the brightness of the blue channel, between 0 and 1.

        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        return await self._get_channel(RGBChannel.BLUE)

    async def set_blue(self, duty_cycle: float) -> None:
        """Set the brightness of the blue channel.

        :raises TypeError: ``duty_cycle`` is not a number (or is a bool).
        :raises ValueError: ``duty_cycle`` is outside [0, 1], or NaN.
        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        await self._set_channel(RGBChannel.BLUE, duty_cycle)

    async def get_colour(self) -> RGBColour:
        """Return the colour as a (red, green, blue) tuple of brightnesses in [0, 1].

        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        red, green, blue = [await self._get_channel(channel) for channel in RGBChannel]
        return (red, green, blue)

    async def set_colour(self, colour: RGBColour) -> None:
        """Set all three channels from a (red, green, blue) tuple of brightnesses.

        All three values are checked before any channel is changed.

        :raises TypeError: ``colour`` is not a tuple or list of three numbers.
        :raises ValueError: ``colour`` does not have three values, or one of them is
            outside [0, 1] or NaN.
        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        allowed = f"a (red, green, blue) tuple, each {_DUTY_ALLOWED}"
        if not isinstance(colour, tuple | list):
            raise TypeError(f"RGB LED colour must be {allowed}; got {describe(colour)}")
        if len(colour) != len(RGBChannel):
            raise ValueError(
                f"RGB LED colour must be {allowed}; got {len(colour)} values: {colour!r}",
            )
        duty_cycles = [
            _check_duty_cycle(value, channel)
            for channel, value in zip(RGBChannel, colour, strict=True)
        ]
        for channel, duty_cycle in zip(RGBChannel, duty_cycles, strict=True):
            await self._backend.set_rgb_led_channel_duty_cycle(
                self._identifier, channel, duty_cycle,
            )

    async def _get_channel(self, channel: RGBChannel) -> float:
        return await self._backend.get_rgb_led_channel_duty_cycle(self._identifier, channel)

    async def _set_channel(self, channel: RGBChannel, duty_cycle: float) -> None:
        value = _check_duty_cycle(duty_cycle, channel)
        await self._backend.set_rgb_led_channel_duty_cycle(self._identifier, channel, value)


def _check_duty_cycle(value: object, channel: RGBChannel) -> float:
    """Return ``value`` as the duty cycle of ``channel`` if it is in [0, 1]."""
    return check_number(
        value,
        name=f"RGB LED {channel.name.lower()} duty cycle",
        low=0.0,
        high=1.0,
        allowed=_DUTY_ALLOWED,
    )

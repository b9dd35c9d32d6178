"""Flashing LEDs: LEDs that can also flash on their own."""

from __future__ import annotations

from abc import abstractmethod
from typing import cast

from j5aio.components._checks import check_number
from j5aio.components.led import LED, LEDInterface

__all__ = ["FlashingLED", "FlashingLEDInterface"]

#: The longest flash period accepted, in seconds.
MAX_FLASH_PERIOD = 60.0
#: The shortest flash period accepted, in seconds.
MIN_FLASH_PERIOD = 0.02


class FlashingLEDInterface(LEDInterface):
    """The coroutines a backend implements to drive LEDs that can flash."""

    @abstractmethod
    async def get_led_flashing(self, identifier: int) -> bool:
        """Return whether LED ``identifier`` is flashing."""
        raise NotImplementedError

    @abstractmethod
    async def set_led_flashing(self, identifier: int, period: float) -> None:
        """Flash LED ``identifier``, on for half of ``period`` seconds, off for the other half.

        Setting the LED's state afterwards stops the flashing.
        """
        raise NotImplementedError


class FlashingLED(LED):
    """An LED that is on, off, or flashing by itself.

    ``await led.flash()`` starts it flashing once a second; ``await led.set_state(...)``
    stops the flashing and leaves it on or off.

    :param identifier: the number of the LED on its board.
    :param backend: the backend that drives the LED.
    """

    __slots__ = ()

    @classmethod
    def interface_class(cls) -> type[FlashingLEDInterface]:
        """The interface a backend implements for flashing LEDs: :class:`FlashingLEDInterface`."""
        return FlashingLEDInterface

    @property
    def _flashing(self) -> FlashingLEDInterface:
        return cast(FlashingLEDInterface, self._backend)

    async def flash(self, period: float = 1.0) -> None:
        """Flash the LED: on for half of ``period`` seconds, then off for the other half.

        :raises TypeError: ``period`` is not a number (or is a bool).
        :raises ValueError: ``period`` is outside 0.02 to 60 seconds, or NaN.
        """
        seconds = check_number(
            period,
            name="flash period",
            low=MIN_FLASH_PERIOD,
            high=MAX_FLASH_PERIOD,
            allowed=f"a number of seconds from {MIN_FLASH_PERIOD} to {MAX_FLASH_PERIOD:g}",
        )
        await self._flashing.set_led_flashing(self._identifier, seconds)

    async def get_is_flashing(self) -> bool:
        """Return whether the LED is flashing."""
        return await self._flashing.get_led_flashing(self._identifier)

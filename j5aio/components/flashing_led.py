"""Flashing LEDs: an LED that is off, on, or flashing by itself."""

from __future__ import annotations

from abc import abstractmethod
from enum import Enum
from typing import cast

from j5aio.components._checks import describe
from j5aio.components.led import LED, LEDInterface

__all__ = ["FlashingLED", "FlashingLEDInterface", "LEDMode"]


class LEDMode(Enum):
    """What an LED that can flash by itself is doing."""

    OFF = "off"  #: dark
    ON = "on"  #: lit
    FLASH = "flash"  #: the board toggles it on its own (once a second on the SR power board)


class FlashingLEDInterface(LEDInterface):
    """The coroutines a backend implements to drive LEDs that can flash by themselves.

    ``get_led_state`` / ``set_led_state`` of :class:`~j5aio.components.led.LEDInterface` still work:
    a flashing LED reads as lit, and setting a state stops the flashing.
    """

    @abstractmethod
    async def get_led_mode(self, identifier: int) -> LEDMode:
        """Return what LED ``identifier`` is doing."""
        raise NotImplementedError

    @abstractmethod
    async def set_led_mode(self, identifier: int, mode: LEDMode) -> None:
        """Switch LED ``identifier`` off, on, or to flashing."""
        raise NotImplementedError


class FlashingLED(LED):
    """An LED that can be off, on, or flashing without the program's help.

    It is an :class:`~j5aio.components.led.LED` too: ``set_state(True)`` lights it
    steadily, and ``get_state()`` is ``True`` while it is lit or flashing. Use
    ``await led.set_mode(LEDMode.FLASH)`` to make it flash.

    :param identifier: the number of the LED on its board.
    :param backend: the backend that drives the LED.
    """

    __slots__ = ()

    @classmethod
    def interface_class(cls) -> type[FlashingLEDInterface]:
        """The interface a backend implements: :class:`FlashingLEDInterface`."""
        return FlashingLEDInterface

    async def get_mode(self) -> LEDMode:
        """Return whether the LED is off, on or flashing.

        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        return await cast(FlashingLEDInterface, self._backend).get_led_mode(self._identifier)

    async def set_mode(self, mode: LEDMode) -> None:
        """Switch the LED off, on, or to flashing.

        :raises TypeError: ``mode`` is not an :class:`LEDMode`.
        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        if not isinstance(mode, LEDMode):
            raise TypeError(
                "LED mode must be LEDMode.OFF, LEDMode.ON or LEDMode.FLASH; "
                f"got {describe(mode)}",
            )
        await cast(FlashingLEDInterface, self._backend).set_led_mode(self._identifier, mode)

    async def flash(self) -> None:
        """Make the LED flash by itself: the same as ``set_mode(LEDMode.FLASH)``.

        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        await self.set_mode(LEDMode.FLASH)

"""LEDs: a light that is on or off."""

from __future__ import annotations

from abc import abstractmethod

from j5aio.components._checks import check_bool
from j5aio.components.component import Interface
from j5aio.components.identified import IdentifiedComponent

__all__ = ["LED", "LEDInterface"]


class LEDInterface(Interface):
    """The coroutines a backend implements to drive LEDs."""

    @abstractmethod
    async def get_led_state(self, identifier: int) -> bool:
        """Return whether LED ``identifier`` is lit."""
        raise NotImplementedError

    @abstractmethod
    async def set_led_state(self, identifier: int, state: bool) -> None:
        """Light (``True``) or darken (``False``) LED ``identifier``."""
        raise NotImplementedError


class LED(IdentifiedComponent[LEDInterface]):
    """A light on a board that is either on or off.

    Turn it on with ``await led.set_state(True)`` and off with ``await led.set_state(False)``.

    :param identifier: the number of the LED on its board.
    :param backend: the backend that drives the LED.
    """

    __slots__ = ()

    @classmethod
    def interface_class(cls) -> type[LEDInterface]:
        """The interface a backend implements to drive LEDs: :class:`LEDInterface`."""
        return LEDInterface

    async def get_state(self) -> bool:
        """Return ``True`` if the LED is lit, ``False`` if it is dark.

        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        return await self._backend.get_led_state(self._identifier)

    async def set_state(self, state: bool) -> None:
        """Light the LED (``True``) or darken it (``False``).

        :raises TypeError: ``state`` is not a bool; ``1`` and ``0`` are refused as well.
        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        check_bool(state, name="LED state", allowed="True (on) or False (off)")
        await self._backend.set_led_state(self._identifier, state)

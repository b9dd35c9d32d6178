"""LEDs: a light that is on or off."""

from __future__ import annotations

from abc import abstractmethod

from j5aio.components.component import Interface

__all__ = ["LEDInterface"]


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

"""Buttons: a switch the user can press, such as the start button."""

from __future__ import annotations

from abc import abstractmethod

from j5aio.components.component import Interface

__all__ = ["ButtonInterface"]


class ButtonInterface(Interface):
    """The coroutines a backend implements to read buttons."""

    @abstractmethod
    async def get_button_state(self, identifier: int) -> bool:
        """Return whether button ``identifier`` is pressed."""
        raise NotImplementedError

    @abstractmethod
    async def wait_until_button_pressed(self, identifier: int) -> None:
        """Return once button ``identifier`` has been pressed.

        Must be cancellable: the component applies any timeout by cancelling this call.
        """
        raise NotImplementedError

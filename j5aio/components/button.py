"""Buttons: a switch the user can press, such as the start button."""

from __future__ import annotations

from abc import abstractmethod
from typing import ClassVar

import anyio

from j5aio.components._checks import check_timeout
from j5aio.components.component import Interface
from j5aio.components.identified import IdentifiedComponent

__all__ = ["Button", "ButtonInterface"]


class ButtonInterface(Interface):
    """The coroutines a backend implements to read buttons."""

    #: Whether a board waiting for its start button (``wait_for_start_flash``) should
    #: await :meth:`wait_until_button_pressed`, which ends soon after a press at little
    #: cost (``True``, the default), or keep looking with :meth:`get_button_state`, as
    #: j5 does (``False``: the console, whose every look is a question to the user).
    WAITS_FOR_PRESSES: ClassVar[bool] = True

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


class Button(IdentifiedComponent[ButtonInterface]):
    """A button the user can press, such as the start button of a robot.

    :param identifier: the number of the button on its board.
    :param backend: the backend that reads the button.
    """

    __slots__ = ()

    @classmethod
    def interface_class(cls) -> type[ButtonInterface]:
        """The interface a backend implements to read buttons: :class:`ButtonInterface`."""
        return ButtonInterface

    async def get_is_pressed(self) -> bool:
        """Return ``True`` if the button is held down right now.

        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        return await self._backend.get_button_state(self._identifier)

    async def wait_until_pressed(self, timeout: float | None = None) -> None:
        """Wait until the button is pressed.

        Other tasks keep running while this one waits, and the wait can be cancelled.

        :param timeout: give up after this many seconds; ``None`` (the default) waits
            for as long as it takes.
        :raises TimeoutError: ``timeout`` seconds passed before the button was pressed.
        :raises TypeError: ``timeout`` is not ``None`` or a number.
        :raises ValueError: ``timeout`` is negative or NaN.
        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        if timeout is None:  # no deadline to keep: the backend's wait is the whole of it
            await self._backend.wait_until_button_pressed(self._identifier)
            return
        limit = check_timeout(timeout)
        with anyio.move_on_after(limit) as scope:
            await self._backend.wait_until_button_pressed(self._identifier)
        if scope.cancelled_caught:
            raise TimeoutError(
                f"the button was not pressed within {timeout} s; pass a longer timeout, "
                "or timeout=None to wait for as long as it takes",
            )

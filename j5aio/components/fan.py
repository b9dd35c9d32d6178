"""Fans: a cooling fan the board runs by itself."""

from __future__ import annotations

from abc import abstractmethod

from j5aio.components.component import Interface
from j5aio.components.identified import IdentifiedComponent

__all__ = ["Fan", "FanInterface"]


class FanInterface(Interface):
    """The coroutines a backend implements to read fans."""

    @abstractmethod
    async def get_fan_running(self, identifier: int) -> bool:
        """Return whether fan ``identifier`` is running."""
        raise NotImplementedError


class Fan(IdentifiedComponent[FanInterface]):
    """A cooling fan that the board switches on when it gets warm.

    :param identifier: the number of the fan on its board.
    :param backend: the backend that reads the fan.
    """

    __slots__ = ()

    @classmethod
    def interface_class(cls) -> type[FanInterface]:
        """The interface a backend implements: :class:`FanInterface`."""
        return FanInterface

    async def get_is_running(self) -> bool:
        """Return ``True`` if the fan is running.

        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        return await self._backend.get_fan_running(self._identifier)

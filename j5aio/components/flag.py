"""Flags: a yes-or-no condition a board reports, such as "power good"."""

from __future__ import annotations

from abc import abstractmethod

from j5aio.components.component import Interface
from j5aio.components.identified import IdentifiedComponent

__all__ = ["Flag", "FlagInterface"]


class FlagInterface(Interface):
    """The coroutines a backend implements to read flags."""

    @abstractmethod
    async def get_flag_state(self, identifier: int) -> bool:
        """Return whether flag ``identifier`` is raised."""
        raise NotImplementedError


class Flag(IdentifiedComponent[FlagInterface]):
    """A condition a board reports as raised (``True``) or not (``False``).

    What a flag means is given by the name the board gives it, for example a servo
    board's ``power_good`` and ``watchdog_failed``.

    :param identifier: the number of the flag on its board.
    :param backend: the backend that reads the flag.
    """

    __slots__ = ()

    @classmethod
    def interface_class(cls) -> type[FlagInterface]:
        """The interface a backend implements to read flags: :class:`FlagInterface`."""
        return FlagInterface

    async def get_state(self) -> bool:
        """Return ``True`` if the flag is raised.

        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        return await self._backend.get_flag_state(self._identifier)

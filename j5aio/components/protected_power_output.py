"""Protected power outputs: a power output that switches itself off on over-current."""

from __future__ import annotations

from abc import abstractmethod
from typing import cast

from j5aio.components.power_output import PowerOutput, PowerOutputInterface

__all__ = ["ProtectedPowerOutput", "ProtectedPowerOutputInterface"]


class ProtectedPowerOutputInterface(PowerOutputInterface):
    """The coroutines a backend implements for power outputs with over-current protection."""

    @abstractmethod
    async def get_power_output_overcurrent(self, identifier: int) -> bool:
        """Return whether output ``identifier`` is latched off by its over-current trip."""
        raise NotImplementedError


class ProtectedPowerOutput(PowerOutput):
    """A power output that the board switches off, and keeps off, when it draws too much.

    While the trip is latched, switching the output on does nothing; the board clears
    the latch only when it is reset.

    :param identifier: the number of the output on its board.
    :param backend: the backend that drives the output.
    """

    __slots__ = ()

    @classmethod
    def interface_class(cls) -> type[ProtectedPowerOutputInterface]:
        """The interface a backend implements: :class:`ProtectedPowerOutputInterface`."""
        return ProtectedPowerOutputInterface

    async def get_is_overcurrent(self) -> bool:
        """Return ``True`` if the output has been switched off for drawing too much current.

        :raises CommunicationError: the board did not answer, or answered wrongly.
        """
        backend = cast(ProtectedPowerOutputInterface, self._backend)
        return await backend.get_power_output_overcurrent(self._identifier)

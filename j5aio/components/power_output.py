"""Power outputs: a switchable supply on a power board, with a current meter."""

from __future__ import annotations

from abc import abstractmethod

from j5aio.components.component import Interface

__all__ = ["PowerOutputInterface"]


class PowerOutputInterface(Interface):
    """The coroutines a backend implements to drive power outputs."""

    @abstractmethod
    async def get_power_output_enabled(self, identifier: int) -> bool:
        """Return whether output ``identifier`` is switched on."""
        raise NotImplementedError

    @abstractmethod
    async def set_power_output_enabled(self, identifier: int, enabled: bool) -> None:
        """Switch output ``identifier`` on or off."""
        raise NotImplementedError

    @abstractmethod
    async def get_power_output_current(self, identifier: int) -> float:
        """Return the current drawn from output ``identifier``, in amps."""
        raise NotImplementedError

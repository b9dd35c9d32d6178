"""The Bee Board's simulated backend: its hardware backend, on the simulated kit."""

from __future__ import annotations

from collections.abc import Sequence

from j5aio.backends.hardware.options import DiscoveryOptions
from j5aio.simulator.discovery import kind_options

from .backend import BeeBackend
from .boards import BeeBoard

__all__ = ["BeeSimulatedBackend"]


class BeeSimulatedBackend(BeeBackend):
    """:class:`~beekit.backend.BeeBackend` on the simulated kit: only ``discover`` differs."""

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[BeeBoard]:
        """Find the current simulated kit's Bee Boards (or those ``options`` find)."""
        return await super().discover(options=options or kind_options(cls))

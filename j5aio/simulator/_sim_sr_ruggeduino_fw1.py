"""The Ruggeduino (firmware 1): its simulated backend."""

from __future__ import annotations

from collections.abc import Sequence

from j5aio.backends.hardware.options import DiscoveryOptions
from j5aio.backends.hardware.sr.v4.ruggeduino import SRV4RuggeduinoHardwareBackend
from j5aio.boards.sr.v4 import Ruggeduino

from .discovery import kind_options

__all__ = ["SRV4RuggeduinoSimulatedBackend"]


class SRV4RuggeduinoSimulatedBackend(SRV4RuggeduinoHardwareBackend):
    """The Ruggeduino (firmware 1) hardware backend, on the simulated kit."""

    __module__ = "j5aio.simulator.sim_backends"  # where it is documented, and imported from

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[Ruggeduino]:
        """Find the current simulated kit's boards of this kind (or those ``options`` find)."""
        return await super().discover(options=options or kind_options(cls))

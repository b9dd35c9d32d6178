"""The SR Arduino (firmware 2): its simulated backend."""

from __future__ import annotations

from collections.abc import Sequence

from j5aio.backends.hardware.options import DiscoveryOptions
from j5aio.backends.hardware.sr.v4.arduino import SRArduinoHardwareBackend
from j5aio.boards.sr.v4 import SRArduinoBoard

from .discovery import kind_options

__all__ = ["SRArduinoSimulatedBackend"]


class SRArduinoSimulatedBackend(SRArduinoHardwareBackend):
    """The SR Arduino (firmware 2) hardware backend, on the simulated kit."""

    __module__ = "j5aio.simulator.sim_backends_2023"  # where it is documented, and imported from

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[SRArduinoBoard]:
        """Find the current simulated kit's boards of this kind (or those ``options`` find)."""
        return await super().discover(options=options or kind_options(cls))

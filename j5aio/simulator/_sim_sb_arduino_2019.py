"""The SourceBots Arduino (2019 firmware): its simulated backend."""

from __future__ import annotations

from collections.abc import Sequence

from j5aio.backends.hardware.options import DiscoveryOptions
from j5aio.backends.hardware.sb.arduino import SBArduinoHardwareBackend
from j5aio.boards.sb import SBArduinoBoard

from .discovery import kind_options

__all__ = ["SBArduinoSimulatedBackend"]


class SBArduinoSimulatedBackend(SBArduinoHardwareBackend):
    """The SourceBots Arduino (2019 firmware) hardware backend, on the simulated kit."""

    __module__ = "j5aio.simulator.sim_backends"  # where it is documented, and imported from

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[SBArduinoBoard]:
        """Find the current simulated kit's boards of this kind (or those ``options`` find)."""
        return await super().discover(options=options or kind_options(cls))

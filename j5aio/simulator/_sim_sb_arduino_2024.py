"""The SourceBots Arduino (sb2024 firmware): its simulated backend."""

from __future__ import annotations

from collections.abc import Sequence

from j5aio.backends.hardware.options import DiscoveryOptions
from j5aio.backends.hardware.sb.arduino_2024 import SBArduino2024HardwareBackend
from j5aio.boards.sb import SBArduino2024Board

from .discovery import kind_options

__all__ = ["SBArduino2024SimulatedBackend"]


class SBArduino2024SimulatedBackend(SBArduino2024HardwareBackend):
    """The SourceBots Arduino (sb2024 firmware) hardware backend, on the simulated kit."""

    __module__ = "j5aio.simulator.sim_backends_2023"  # where it is documented, and imported from

    @classmethod
    async def discover(
        cls, *, options: DiscoveryOptions | None = None
    ) -> Sequence[SBArduino2024Board]:
        """Find the current simulated kit's boards of this kind (or those ``options`` find)."""
        return await super().discover(options=options or kind_options(cls))

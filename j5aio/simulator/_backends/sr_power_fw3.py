"""The SR v4 power board (firmware 3): its simulated backend."""

from __future__ import annotations

from collections.abc import Sequence

from j5aio.backends.hardware.options import DiscoveryOptions
from j5aio.backends.hardware.sr.v4.power_board import SRV4PowerBoardHardwareBackend
from j5aio.boards.board import Board

from ..discovery import kind_options

__all__ = ["SRV4PowerBoardSimulatedBackend"]


class SRV4PowerBoardSimulatedBackend(SRV4PowerBoardHardwareBackend):
    """The SR v4 power board (firmware 3) hardware backend, on the simulated kit."""

    __module__ = "j5aio.simulator.sim_backends"  # where it is documented, and imported from

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[Board]:
        """Find the current simulated kit's boards of this kind (or those ``options`` find)."""
        return await super().discover(options=options or kind_options(cls))

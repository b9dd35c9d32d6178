"""The simulated backends of the servo boards of firmware 4 (SR's 4.3, SourceBots' 4.4)."""

from __future__ import annotations

from collections.abc import Sequence

from j5aio.backends.hardware.options import DiscoveryOptions
from j5aio.backends.hardware.sr.v4.servo_board_fw4 import (
    SBServoBoardHardwareBackend,
    SRV4ServoBoardFw4HardwareBackend,
)
from j5aio.boards.board import Board

from ..discovery import kind_options

__all__ = ["SBServoBoardSimulatedBackend", "SRV4ServoBoardFw4SimulatedBackend"]


class SRV4ServoBoardFw4SimulatedBackend(SRV4ServoBoardFw4HardwareBackend):
    """The SR v4 servo board (firmware 4.3) hardware backend, on the simulated kit."""

    __module__ = "j5aio.simulator.sim_backends_2023"  # where it is documented, and imported from

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[Board]:
        """Find the current simulated kit's boards of this kind (or those ``options`` find)."""
        return await super().discover(options=options or kind_options(cls))


class SBServoBoardSimulatedBackend(SBServoBoardHardwareBackend):
    """The SourceBots servo board (firmware 4.4) hardware backend, on the simulated kit."""

    __module__ = "j5aio.simulator.sim_backends_2023"  # where it is documented, and imported from

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[Board]:
        """Find the current simulated kit's boards of this kind (or those ``options`` find)."""
        return await super().discover(options=options or kind_options(cls))

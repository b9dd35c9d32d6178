"""The simulated backends of the boards of the kits from 2023 on (firmware 4, the sb2024 Arduino).

As in :mod:`j5aio.simulator.sim_backends`: each is the board's hardware backend whose
``discover`` looks at the boards of :func:`~j5aio.simulator.kit.current_kit` made from its
kind's simulators, and nothing else. They live apart from the older boards' so that a
program on an older kit imports none of these boards' backends.
"""

from __future__ import annotations

from collections.abc import Sequence

from j5aio.backends.hardware.options import DiscoveryOptions
from j5aio.backends.hardware.sb.arduino_2024 import SBArduino2024HardwareBackend
from j5aio.backends.hardware.sr.v4.arduino import SRArduinoHardwareBackend
from j5aio.backends.hardware.sr.v4.motor_board_fw4 import SRV4MotorBoardFw4HardwareBackend
from j5aio.backends.hardware.sr.v4.power_board_fw4 import SRV4PowerBoardFw4HardwareBackend
from j5aio.backends.hardware.sr.v4.servo_board_fw4 import (
    SBServoBoardHardwareBackend,
    SRV4ServoBoardFw4HardwareBackend,
)
from j5aio.boards.board import Board
from j5aio.boards.sb import SBArduino2024Board
from j5aio.boards.sr.v4 import SRArduinoBoard

from .discovery import kind_options

__all__ = [
    "SBArduino2024SimulatedBackend",
    "SBServoBoardSimulatedBackend",
    "SRArduinoSimulatedBackend",
    "SRV4MotorBoardFw4SimulatedBackend",
    "SRV4PowerBoardFw4SimulatedBackend",
    "SRV4ServoBoardFw4SimulatedBackend",
]


class SRV4PowerBoardFw4SimulatedBackend(SRV4PowerBoardFw4HardwareBackend):
    """The SR v4 power board (firmware 4) hardware backend, on the simulated kit."""

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[Board]:
        """Find the current simulated kit's boards of this kind (or those ``options`` find)."""
        return await super().discover(options=options or kind_options(cls))


class SRV4MotorBoardFw4SimulatedBackend(SRV4MotorBoardFw4HardwareBackend):
    """The SR v4 motor board (firmware 4) hardware backend, on the simulated kit."""

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[Board]:
        """Find the current simulated kit's boards of this kind (or those ``options`` find)."""
        return await super().discover(options=options or kind_options(cls))


class SRV4ServoBoardFw4SimulatedBackend(SRV4ServoBoardFw4HardwareBackend):
    """The SR v4 servo board (firmware 4.3) hardware backend, on the simulated kit."""

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[Board]:
        """Find the current simulated kit's boards of this kind (or those ``options`` find)."""
        return await super().discover(options=options or kind_options(cls))


class SBServoBoardSimulatedBackend(SBServoBoardHardwareBackend):
    """The SourceBots servo board (firmware 4.4) hardware backend, on the simulated kit."""

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[Board]:
        """Find the current simulated kit's boards of this kind (or those ``options`` find)."""
        return await super().discover(options=options or kind_options(cls))


class SRArduinoSimulatedBackend(SRArduinoHardwareBackend):
    """The SR Arduino (firmware 2) hardware backend, on the simulated kit."""

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[SRArduinoBoard]:
        """Find the current simulated kit's boards of this kind (or those ``options`` find)."""
        return await super().discover(options=options or kind_options(cls))


class SBArduino2024SimulatedBackend(SBArduino2024HardwareBackend):
    """The SourceBots Arduino (sb2024 firmware) hardware backend, on the simulated kit."""

    @classmethod
    async def discover(
        cls, *, options: DiscoveryOptions | None = None
    ) -> Sequence[SBArduino2024Board]:
        """Find the current simulated kit's boards of this kind (or those ``options`` find)."""
        return await super().discover(options=options or kind_options(cls))

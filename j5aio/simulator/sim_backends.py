"""The simulated backends of the SR v4 boards of firmware 3 (and 2) and the 2019 Arduinos.

Each is the board's hardware backend whose ``discover`` looks at the boards of
:func:`~j5aio.simulator.kit.current_kit` made from its kind's simulators (see
:mod:`j5aio.simulator.discovery`), and nothing else: from there on every call runs the
hardware backend's own code (its polls included) over a simulated transport, as on a
robot. Each board kind names its simulated backend (``simulated=`` of
:class:`~j5aio.board_kinds.BoardKind`); the simulated environment imports this module the
first time it needs one of them. The later boards' are in
:mod:`j5aio.simulator.sim_backends_2023`.

A plugin's simulated backend is written the same way, with
:func:`~j5aio.simulator.discovery.kind_options`::

    class BeeSimulatedBackend(BeeBackend):
        @classmethod
        async def discover(cls, *, options=None):
            return await super().discover(options=options or kind_options(cls))
"""

from __future__ import annotations

from collections.abc import Sequence

from j5aio.backends.hardware.options import DiscoveryOptions
from j5aio.backends.hardware.sb.arduino import SBArduinoHardwareBackend
from j5aio.backends.hardware.sr.v4.motor_board import SRV4MotorBoardHardwareBackend
from j5aio.backends.hardware.sr.v4.power_board import SRV4PowerBoardHardwareBackend
from j5aio.backends.hardware.sr.v4.ruggeduino import SRV4RuggeduinoHardwareBackend
from j5aio.backends.hardware.sr.v4.servo_board import SRV4ServoBoardHardwareBackend
from j5aio.boards.board import Board
from j5aio.boards.sb import SBArduinoBoard
from j5aio.boards.sr.v4 import Ruggeduino

from .discovery import kind_options

__all__ = [
    "SBArduinoSimulatedBackend",
    "SRV4MotorBoardSimulatedBackend",
    "SRV4PowerBoardSimulatedBackend",
    "SRV4RuggeduinoSimulatedBackend",
    "SRV4ServoBoardSimulatedBackend",
]


class SRV4PowerBoardSimulatedBackend(SRV4PowerBoardHardwareBackend):
    """The SR v4 power board (firmware 3) hardware backend, on the simulated kit."""

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[Board]:
        """Find the current simulated kit's boards of this kind (or those ``options`` find)."""
        return await super().discover(options=options or kind_options(cls))


class SRV4MotorBoardSimulatedBackend(SRV4MotorBoardHardwareBackend):
    """The SR v4 motor board (firmware 3) hardware backend, on the simulated kit."""

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[Board]:
        """Find the current simulated kit's boards of this kind (or those ``options`` find)."""
        return await super().discover(options=options or kind_options(cls))


class SRV4ServoBoardSimulatedBackend(SRV4ServoBoardHardwareBackend):
    """The SR v4 servo board (firmware 2) hardware backend, on the simulated kit."""

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[Board]:
        """Find the current simulated kit's boards of this kind (or those ``options`` find)."""
        return await super().discover(options=options or kind_options(cls))


class SBArduinoSimulatedBackend(SBArduinoHardwareBackend):
    """The SourceBots Arduino (2019 firmware) hardware backend, on the simulated kit."""

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[SBArduinoBoard]:
        """Find the current simulated kit's boards of this kind (or those ``options`` find)."""
        return await super().discover(options=options or kind_options(cls))


class SRV4RuggeduinoSimulatedBackend(SRV4RuggeduinoHardwareBackend):
    """The Ruggeduino (firmware 1) hardware backend, on the simulated kit."""

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[Ruggeduino]:
        """Find the current simulated kit's boards of this kind (or those ``options`` find)."""
        return await super().discover(options=options or kind_options(cls))
